"""Every file Gearhead writes (presets, workbooks, exports, settings) is written here, one way:
whole or not at all.

The text goes to a temporary file beside the target (same folder, so the final rename is atomic),
is flushed and fsynced, takes the replaced file's mode, and then replaces the target in one rename
(or, for a new file, is hard-linked into place, which fails if the name was taken meanwhile). A
symlink is written through: its target gets the new text, the link stays a link. On Linux the
temporary file is anonymous (O_TMPFILE), so a process killed mid-save leaves nothing behind; where
that is not supported it has a hidden name and is removed on any failure we live through.

Any failure (a full disk, a read-only folder, /proc, /dev/null/x, a name too long, ~nosuchuser)
leaves the old file as it was and raises WriteError naming the path and the reason. WriteError is
an InputError (the CLI exits 2 with its one line) and an OSError (callers that catch OSError, as the
app's settings do, keep working)."""

from __future__ import annotations

import errno as _errno
import os
import secrets
import stat
from pathlib import Path

from .errors import InputError


class WriteError(InputError, OSError):
    """A file could not be written; nothing was changed. `field` says which option or file it was
    (e.g. "--preset-out"), `reason` why, `source` the path."""

    def __init__(self, field: str, reason: str, path: str | os.PathLike, code: int | None = None):
        super().__init__(field, f"cannot write ({reason})", os.fspath(path))
        self._text = ValueError.__str__(self)  # InputError's one line, not OSError's "[Errno n] ..."
        self.reason = reason
        self.errno = code
        self.strerror = reason
        self.filename = os.fspath(path)

    def __str__(self) -> str:
        return self._text


class FileExists(WriteError):
    """The target exists and the caller did not ask to replace it."""

    def __init__(
        self, field: str, path: str | os.PathLike, message: str = "file exists; choose another name"
    ):
        super().__init__(field, "file exists", path, _errno.EEXIST)
        self.message = message
        self._text = InputError(field, message, os.fspath(path)).args[0]


def expand(path: str | os.PathLike, field: str = "file") -> Path:
    """`path` with ~ and ~user expanded. pathlib's expanduser raises RuntimeError for an unknown
    user; here it is a WriteError naming the path."""
    text = os.fspath(path)
    if "\0" in text:
        raise WriteError(field, "the name holds a NUL character", text.replace("\0", "\\0"))
    if not text.strip():
        raise WriteError(field, "no file name given", text)
    if text.startswith("~"):
        expanded = os.path.expanduser(text)
        if expanded == text:  # ~nosuchuser, or no home directory
            user = text[1:].split(os.sep, 1)[0]
            why = f"no user named {user!r}" if user else "no home directory"
            raise WriteError(field, why, text)
        text = expanded
    return Path(text)


def write_text(
    path: str | os.PathLike,
    text: str,
    *,
    overwrite: bool = False,
    field: str = "file",
    encoding: str = "utf-8",
) -> Path:
    """Write `text` to `path` atomically (see the module's note). Without `overwrite`, an existing
    `path` raises FileExists. Returns the path as given (expanded), not the symlink's target."""
    return write_bytes(path, text.encode(encoding), overwrite=overwrite, field=field)


def write_bytes(
    path: str | os.PathLike, data: bytes, *, overwrite: bool = False, field: str = "file"
) -> Path:
    path = expand(path, field)
    target = path
    try:
        if os.path.islink(path):  # write through the link: its target gets the text
            target = Path(os.path.realpath(path))
        try:
            old = os.stat(target)
        except FileNotFoundError:
            old = None
        if old is not None and not overwrite:
            raise FileExists(field, path)
        if old is not None and not stat.S_ISREG(old.st_mode):  # a folder, /dev/null, a FIFO
            raise WriteError(field, "not a regular file", path)
        if old is not None:
            # a rename needs only the folder's permission: a read-only file would be replaced.
            # Opened for writing (not truncated) as before this helper: refused the same way
            os.close(os.open(target, os.O_WRONLY))
        try:
            _write(target, data, old, overwrite, field, _ANONYMOUS["ok"])
        except _CannotName:  # /proc's link refused (a locked-down container): a named temporary
            _write(target, data, old, overwrite, field, False)
    except WriteError:
        raise
    except (OSError, ValueError) as exc:  # ValueError: e.g. a name the OS cannot encode
        reason = getattr(exc, "strerror", None) or str(exc) or type(exc).__name__
        raise WriteError(field, reason, path, getattr(exc, "errno", None)) from None
    return path


class _CannotName(Exception):
    """An anonymous temporary file could not be given a name (linkat through /proc refused)."""


def _write(
    target: Path, data: bytes, old: os.stat_result | None, overwrite: bool, field: str, anonymous: bool
) -> None:
    folder = target.parent
    mode = None if old is None else stat.S_IMODE(old.st_mode)
    fd, tmp = _temporary(folder, anonymous)
    try:
        view = memoryview(data)
        while view:  # os.write may write less than asked
            view = view[os.write(fd, view) :]
        if old is not None:  # keep the replaced file's owner, then mode (a save made 0664 0600)
            _keep_owner(fd, old)  # first: a change of owner may clear set-id bits
            if tmp is None:
                os.fchmod(fd, mode)
            else:
                os.chmod(tmp, mode)  # by name: os.fchmod is not on Windows before Python 3.13
        os.fsync(fd)
        if tmp is None:  # anonymous and whole: name it (linkat following /proc's link to the file)
            link = _linker(fd)
            if not overwrite:
                try:
                    link(target)  # fails if the name was taken meanwhile
                except FileExistsError:
                    raise FileExists(field, target) from None
                except OSError as exc:
                    raise _CannotName from exc
                _sync_folder(folder)
                return
            try:
                tmp = _hidden_name(folder, link)
            except OSError as exc:
                raise _CannotName from exc
        if overwrite:
            os.replace(tmp, target)
        else:
            _place_new(tmp, target, field)
        tmp = None
        _sync_folder(folder)
    finally:
        os.close(fd)
        if tmp is not None and os.path.lexists(tmp):
            os.unlink(tmp)


# O_TMPFILE (Linux) with /proc to name the file once written (tests switch it off to try the other way)
_ANONYMOUS = {"ok": hasattr(os, "O_TMPFILE") and os.path.isdir("/proc/self/fd")}


def _keep_owner(fd: int, old: os.stat_result) -> None:
    """The replaced file's owner and group, where we may set them (root saving a user's file;
    a group we belong to). Not being allowed is not a failure: the mode is what matters."""
    if not hasattr(os, "fchown") or (old.st_uid, old.st_gid) == (os.geteuid(), os.getegid()):
        return
    try:
        os.fchown(fd, old.st_uid, old.st_gid)
    except OSError:
        pass


def _linker(fd: int):
    """A function giving the anonymous file open as `fd` a name. os.link calls link(2), which
    would link /proc's symlink itself; a src_dir_fd makes it linkat(2) with AT_SYMLINK_FOLLOW."""

    def link(name: Path) -> None:
        proc = os.open("/proc/self/fd", os.O_RDONLY)
        try:
            os.link(str(fd), name, src_dir_fd=proc, follow_symlinks=True)
        finally:
            os.close(proc)

    return link


def _temporary(folder: Path, anonymous: bool) -> tuple[int, Path | None]:
    """An open file in `folder` to write into: anonymous (None) where O_TMPFILE works, else a new
    hidden name. Created 0666 less the umask, as any new file (mkstemp would make it 0600)."""
    if anonymous:
        try:
            return os.open(folder, os.O_TMPFILE | os.O_WRONLY, 0o666), None
        except OSError as exc:
            if exc.errno not in (_errno.EOPNOTSUPP, _errno.EISDIR, _errno.EINVAL):
                raise  # a real failure (no folder, read-only, no space): the same for a named file
            # this file system cannot (e.g. some network ones): a named file, for this write only
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    fds: list[int] = []
    tmp = _hidden_name(folder, lambda name: fds.append(os.open(name, flags, 0o666)))
    return fds[0], tmp


def _hidden_name(folder: Path, create) -> Path:
    """A new hidden name in `folder`, made by `create(name)` (which fails if the name exists)."""
    while True:
        name = folder / f".gearhead-{secrets.token_hex(6)}.tmp"
        try:
            create(name)
            return name
        except FileExistsError:
            continue


def _place_new(tmp: Path, path: Path, field: str) -> None:
    """Move the written `tmp` to `path`, which must not exist: a hard link fails if it does, and
    the whole file appears at once. Where hard links are not supported, an exclusively created
    empty file claims the name and the temporary file then replaces it."""
    try:
        os.link(tmp, path)
        os.unlink(tmp)
        return
    except FileExistsError:
        raise FileExists(field, path) from None
    except (OSError, NotImplementedError, AttributeError) as exc:
        if isinstance(exc, OSError) and exc.errno not in (_errno.EPERM, _errno.EOPNOTSUPP, _errno.ENOSYS):
            raise
    os.close(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
    os.replace(tmp, path)


def _sync_folder(folder: Path) -> None:
    """fsync the folder so the rename itself survives a power cut (best effort: not everywhere)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
