"""python -m sdfgl.hardcases [WxH] [--doc FILE]: print the table, or write docs/hardcases.md."""
import sys
from pathlib import Path

from . import document, table


def main(argv: list[str]) -> None:
    """Print the hard-case table at the size given (default 128x96), or write the document."""
    w, h = (int(x) for x in (argv[0] if argv and not argv[0].startswith("-") else "128x96").split("x"))
    if "--doc" in argv:
        Path(argv[argv.index("--doc") + 1]).write_text(document((w, h)), encoding="utf-8")
    else:
        print(table((w, h)))


if __name__ == "__main__":
    main(sys.argv[1:])
