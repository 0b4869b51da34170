"""OpenGL plumbing: contexts, the program cache and render targets."""
