"""Files written whole or not at all.

Every writer of sdfgl (images, meshes, clips, pages, scene documents, ``.npz`` outputs)
writes under a temporary name beside the target, checks what it wrote, and renames it into
place in one step. A full disk, a failed encoder or an interrupted run leaves the old file
(if any) untouched and no half-written file under the target's name, and the error says
which file and what went wrong.
"""
from __future__ import annotations

import contextlib
import os
from pathlib import Path
from typing import Callable, Iterator

from .errors import SdfglError


def temp_path(path: Path) -> Path:
    """A hidden name beside ``path`` with the same suffix (encoders pick the format from it)."""
    return path.with_name(f".{path.stem}.tmp-{os.getpid()}{path.suffix}")


def flush_to_disk(path: Path) -> None:
    """fsync ``path``, so a disk that fills only at write-back fails here, before the rename."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def cannot_write(what: str, target: Path, exc: OSError) -> SdfglError:
    """The error for an OSError met while writing ``target``."""
    reason = exc.strerror or str(exc)
    return SdfglError(f"cannot write {what} '{target}': {reason}; nothing was written under that name"
                      " (an older file there is untouched)")


def commit(tmp: Path, target: Path, what: str, check: Callable[[Path], None] | None = None) -> None:
    """Flush the finished temporary file ``tmp``, check it with ``check(tmp)`` (which raises
    :class:`SdfglError` on a bad file) and rename it onto ``target``; on any failure ``tmp``
    is removed and ``target`` left as it was."""
    try:
        flush_to_disk(tmp)
        if check is not None:
            check(tmp)
        os.replace(tmp, target)
    except OSError as exc:
        tmp.unlink(missing_ok=True)
        raise cannot_write(what, target, exc) from exc
    except SdfglError as exc:
        tmp.unlink(missing_ok=True)
        raise SdfglError(f"cannot write {what} '{target}': {exc}; nothing was written under that name"
                         " (an older file there is untouched)") from exc
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


@contextlib.contextmanager
def written_atomically(path: str | Path, what: str,
                       check: Callable[[Path], None] | None = None) -> Iterator[Path]:
    """Yield a temporary path to write ``path``'s content to; when the block ends, the file is
    committed (see :func:`commit`). On any failure the temporary file is removed, ``path`` is
    left as it was, and an OSError becomes an :class:`SdfglError` naming ``what`` and the file."""
    target = Path(path)
    tmp = temp_path(target)
    try:
        yield tmp
    except OSError as exc:
        tmp.unlink(missing_ok=True)
        raise cannot_write(what, target, exc) from exc
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    commit(tmp, target, what, check)


def write_bytes_atomically(path: str | Path, data: bytes, what: str) -> Path:
    """Write ``data`` to ``path`` whole or not at all (see :func:`written_atomically`)."""
    target = Path(path)
    with written_atomically(target, what) as tmp:
        tmp.write_bytes(data)
    return target


def write_text_atomically(path: str | Path, text: str, what: str) -> Path:
    """Write UTF-8 ``text`` to ``path`` whole or not at all (see :func:`written_atomically`)."""
    return write_bytes_atomically(path, text.encode("utf-8"), what)
