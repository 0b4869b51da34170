"""Scripts that build sdfgl's benchmark scenes with a peer library, run in a subprocess by the benchmarks."""
