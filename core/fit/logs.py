"""Reading the robot's logs: WPILib's WPILog (allwpilib datalog/doc/datalog.adoc, version 1.0) and
AdvantageScope's CSV export (a timestamp column, then one column per signal).

Our own streaming reader of the documented format, not robotpy's wpiutil.log.DataLogReader: robotpy
is ~30 MB of native wheels the default install does not have, and its reader maps the whole file;
this one reads 64 KiB at a time and skips the payloads of entries nobody asked for, so memory is set
by the signals kept, not by the log's size (the tests check it against DataLogReader, record by record
and signal by signal). Speed (bench/bench_fit.py): the walk from record to record is a loop of one
byte read and two table look-ups (WPILog.scan); the kept entries' records of each chunk are then
decoded together with numpy (read_wpilog), about 0.15 µs a record in all.

Format (datalog.adoc "Header", "Records", "Control Records"), all little-endian:
    header: "WPILOG", u16 version (0x0100), u32 n, n bytes of extra header (UTF-8)              (L1)
    record: u8 bitfield (bits 0-1: entry-id bytes − 1, 2-3: payload-size bytes − 1,
            4-6: timestamp bytes − 1), entry id, payload size, timestamp (µs), payload         (L2)
    entry 0: control: u8 kind; Start (0): u32 id, u32+name, u32+type, u32+metadata;
             Finish (1): u32 id; Set metadata (2): u32 id, u32+metadata                         (L3)
Records need not be in time order (the format allows it): each signal is sorted by time, stably.
"""

from __future__ import annotations

import csv
import math
import os
import re
import struct
from array import array
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError

CHUNK = 1 << 16  # bytes read at a time: 64 KiB (the reader's peak memory is a few of them)
_FAST_MAX = 1 + 4 + 1 + 8 + 255  # the longest record with a one-byte payload size
# per header bitfield (L2): the header's length, and the payload size's offset in it when it is one
# byte (0: longer, read by the general header)
_HL = [1 + (b & 3) + 1 + ((b >> 2) & 3) + 1 + ((b >> 4) & 7) + 1 for b in range(256)]
_OFF = [2 + (b & 3) if (b >> 2) & 3 == 0 else 0 for b in range(256)]
MAGIC = b"WPILOG"
CONTROL_START, CONTROL_FINISH, CONTROL_SET_METADATA = 0, 1, 2
# the fixed-size types read as numbers (datalog.adoc "Data Types"): numpy's little-endian dtype
_DTYPES = {"double": "<f8", "float": "<f4", "int64": "<i8", "boolean": "u1"}
# a CSV number as a log writes it: ASCII digits, a point, an exponent; nan and inf are read (and then
# refused, named) rather than taken as text. Python's float() also takes '1_000' and other scripts'
# digits ('١٢'), which no log writes: such a cell is text, not silently a number.
_NUMBER = re.compile(r"[+-]?(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|nan|inf|infinity)", re.I)
CSV_LINE = 1 << 24  # the longest CSV line read (16 MiB): a file of one endless line is refused
TIME_COLUMNS = ("timestamp", "time", "t", "timestamp (s)", "time (s)", "t (s)")


@dataclass(frozen=True)
class Entry:
    id: int
    name: str
    type: str
    metadata: str


@dataclass(frozen=True)
class Record:
    """One record as stored: entry 0 is a control record; `payload` is None when it was skipped."""

    entry: int
    timestamp: int  # µs
    payload: bytes | None
    offset: int  # byte offset of the record in the file


class Texts(Sequence):
    """A string signal's samples: one code a sample (numpy int32) into `table`, its distinct
    strings in the order first met. A SysId test state repeats a handful of values over millions
    of records: held as a list of str it was ~80 bytes a sample (a 167 MB log: 2.6 million strings,
    ~200 MB); here it is 4. Reads as a sequence of str (indexing, slices as lists, iteration,
    equality with a list)."""

    __hash__ = None  # type: ignore[assignment]  # equal to a list of the same strings

    def __init__(self, codes: np.ndarray | None = None, table: list[str] | None = None) -> None:
        self.codes = np.zeros(0, np.int32) if codes is None else codes
        self.table: list[str] = table if table is not None else []
        self._index = {t: k for k, t in enumerate(self.table)}

    @classmethod
    def of(cls, strings) -> Texts:
        out = cls()
        out.codes = np.fromiter((out.code(t) for t in strings), np.int32)
        return out

    def code(self, text: str) -> int:
        """The code of `text`, added to the table when new."""
        k = self._index.get(text)
        if k is None:
            k = self._index[text] = len(self.table)
            self.table.append(text)
        return k

    def __len__(self) -> int:
        return len(self.codes)

    def __getitem__(self, k):
        if isinstance(k, slice):
            return [self.table[c] for c in self.codes[k].tolist()]
        return self.table[int(self.codes[k])]

    def __iter__(self):
        table = self.table
        for start in range(0, len(self.codes), CHUNK):  # a chunk of codes as ints at a time
            yield from (table[c] for c in self.codes[start : start + CHUNK].tolist())

    def __eq__(self, other) -> bool:
        if isinstance(other, Texts | list | tuple):
            return len(self) == len(other) and all(a == b for a, b in zip(self, other))
        return NotImplemented

    def __repr__(self) -> str:
        return f"Texts({self[:5]!r}{'…' if len(self) > 5 else ''}, {len(self)} samples)"


@dataclass
class Signal:
    """One entry's samples, sorted by time: numbers (an array of float) or strings (Texts)."""

    name: str
    type: str
    metadata: str
    times: array = field(default_factory=lambda: array("d"))  # s
    values: array | Texts = field(default_factory=lambda: array("d"))
    reordered: bool = False  # its records were not in time order (sorted here)

    def numeric(self) -> bool:
        return isinstance(self.values, array)


def shown_name(name: str) -> str:
    """An entry's name as it is read, shown and matched: the name itself when it is valid UTF-8,
    printable and has no backslash (every name a robot program logs); else escaped, so that two
    distinct names never look the same and each can be typed back: a backslash as \\\\, a byte
    that is not UTF-8 as \\xNN (80-ff), an invisible character as \\xNN (below 80), \\uNNNN or
    \\UNNNNNNNN. `name` is the bytes decoded with surrogateescape (os.fsdecode's, as a command
    line's argument is), so a name typed in a shell with its raw bytes is shown the same."""
    if name.isprintable() and "\\" not in name:
        return name
    out = []
    for ch in name:
        o = ord(ch)
        if ch == "\\":
            out.append("\\\\")
        elif 0xDC80 <= o <= 0xDCFF:  # surrogateescape's: the byte o - 0xDC00, not UTF-8
            out.append(f"\\x{o - 0xDC00:02x}")
        elif ch.isprintable():
            out.append(ch)
        else:
            out.append(f"\\x{o:02x}" if o < 0x80 else f"\\u{o:04x}" if o <= 0xFFFF else f"\\U{o:08x}")
    return "".join(out)


def quoted(name: str) -> str:
    """A name in a message: quoted, as is when printable (a name read is: shown_name), else repr."""
    return f"'{name}'" if name.isprintable() else repr(name)


def _error(path, message: str) -> InputError:
    return InputError("log", message, os.fspath(path))


def _open(path, **text):
    """The log opened for reading (binary, or text with `text`'s encoding and newline), refused
    unless it is a regular file: a FIFO's open waits for a writer and /dev/zero never ends, so
    they are opened without waiting (O_NONBLOCK) and looked at before anything is read. Raises
    OSError as open() does, or the InputError naming what the path is."""
    import stat

    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            what = (
                "a directory"
                if stat.S_ISDIR(mode)
                else "a pipe (FIFO)"
                if stat.S_ISFIFO(mode)
                else "a device"
                if stat.S_ISCHR(mode) or stat.S_ISBLK(mode)
                else "a socket"
                if stat.S_ISSOCK(mode)
                else "not a regular file"
            )
            raise _error(path, f"is {what}, not a log file")
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        return os.fdopen(fd, "r" if text else "rb", **text)
    except BaseException:
        os.close(fd)
        raise


class WPILog:
    """A WPILog file opened for streaming: the header is checked here, records are read lazily."""

    def __init__(self, path):
        self.path = os.fspath(path)
        self.warnings: list[str] = []
        try:
            with _open(self.path) as f:
                self.size = os.fstat(f.fileno()).st_size
                head = f.read(12)
                if len(head) < 12 or head[:6] != MAGIC:
                    raise _error(path, "is not a WPILog (it does not start with the 'WPILOG' header)")
                self.version, n = struct.unpack_from("<HI", head, 6)
                if self.version >> 8 != 1:
                    raise _error(
                        path,
                        f"is WPILog version {self.version >> 8}.{self.version & 0xFF}; only version 1.x is read",
                    )
                if 12 + n > self.size:
                    raise _error(
                        path, f"is cut off in its header (an extra header of {n} bytes is announced)"
                    )
                self.extra_header = f.read(n).decode("utf-8", "replace")
        except OSError as exc:
            raise _error(path, f"cannot be read ({exc.strerror or exc})") from None
        self.start = 12 + n

    def records(self, keep=None, skipped: bool = True) -> Iterator[Record]:
        """Every record in file order (L2), one by one (scan's records, their headers read here).
        A data record whose entry is not in `keep` (a set or dict of ids; None: keep all) has no
        payload read; it is yielded without one when `skipped`, else not at all."""

        def wanted(e: int) -> bool:
            return keep is None or e in keep

        for buf, base, starts, whole in self.scan(wanted):
            for p in starts:
                b = buf[p]
                il, sl, tl = (b & 3) + 1, ((b >> 2) & 3) + 1, ((b >> 4) & 7) + 1
                q = p + 1 + il + sl
                entry = int.from_bytes(buf[p + 1 : p + 1 + il], "little")
                n = int.from_bytes(buf[p + 1 + il : q], "little")
                ts = int.from_bytes(buf[q : q + tl], "little")
                if not whole or (entry != 0 and not wanted(entry)):
                    if skipped:
                        yield Record(entry, ts, None, base + p)
                    continue
                yield Record(entry, ts, bytes(buf[q + tl : q + tl + n]), base + p)

    def scan(self, keep: Callable[[int], bool]) -> Iterator[tuple[bytes, int, list[int], bool]]:
        """The records in file order (L2), a chunk at a time: (buf, base, starts, whole), `starts`
        the offsets in `buf` (at file offset `base`) of its records, in file order, whole (header
        and payload) when `whole`. A record longer than what is read has its payload read when
        `keep(entry)` or it is a control record; else it is skipped in the file, unread, and
        yielded alone, its header only (`whole` False). A record cut off by the end of the file
        ends the reading with a warning (a robot that lost power mid-write leaves one).

        The walk from record to record is the one step that cannot be vectorised (each record's
        length is in its own header): for a payload under 256 bytes (any id and timestamp width)
        it is one byte read and two table look-ups (_OFF, _HL) a record; others, and the last
        bytes of the file, go through the general header."""
        path = self.path
        size = self.size
        HL, OFF = _HL, _OFF
        try:
            f = _open(path)
        except OSError as exc:
            raise _error(path, f"cannot be read ({exc.strerror or exc})") from None
        with f:
            f.seek(self.start)
            base = self.start
            buf = f.read(CHUNK)
            p = 0
            starts: list[int] = []
            while True:
                n = len(buf)
                eof = base + n >= size
                lim = n - _FAST_MAX  # a fast record starting before lim ends inside buf
                app = starts.append
                while p < lim:
                    b = buf[p]
                    o = OFF[b]
                    if not o:
                        break
                    app(p)
                    p += HL[b] + buf[p + o]
                if p >= lim and not eof:  # near the end of what is read: read on
                    if starts:
                        yield buf, base, starts, True
                        starts = []
                    more = f.read(CHUNK)
                    if not more:  # shorter than it was when opened
                        size = base + n
                    buf, base, p = buf[p:] + more, base + p, 0
                    continue
                if p >= n:  # the end of the file, at a record's end
                    break
                b = buf[p]  # one record by its general header (L2)
                il, sl, tl = (b & 3) + 1, ((b >> 2) & 3) + 1, ((b >> 4) & 7) + 1
                hl = 1 + il + sl + tl
                if n - p < hl:  # at the end of the file (else read on above)
                    self.warnings.append(
                        f"{path}: ends in a partial record at byte {base + p}; read up to it"
                    )
                    break
                entry = int.from_bytes(buf[p + 1 : p + 1 + il], "little")
                length = hl + int.from_bytes(buf[p + 1 + il : p + 1 + il + sl], "little")
                end = base + p + length
                if end > size:
                    self.warnings.append(
                        f"{path}: ends in a partial record at byte {base + p} (its {length - hl}-byte payload "
                        f"runs past the end of the file); read up to it"
                    )
                    break
                if p + length <= n:
                    starts.append(p)
                    p += length
                    continue
                if starts:  # the record runs past what is read: the records before it first
                    yield buf, base, starts, True
                    starts = []
                if entry != 0 and not keep(entry):
                    yield buf[p : p + hl], base + p, [0], False
                    f.seek(end)
                    base, buf, p = end, f.read(CHUNK), 0
                    continue
                more = f.read(length - (n - p))
                if len(more) < length - (n - p):  # shorter than it was when opened
                    size = base + n + len(more)
                buf, base, p = buf[p:] + more, base + p, 0
            if starts:
                yield buf, base, starts, True

    def control(self, rec: Record) -> tuple[int, Entry | int | tuple[int, str]]:
        """A control record's kind and contents (L3): Start -> Entry, Finish -> id,
        Set metadata -> (id, metadata). A malformed one is refused naming its byte offset."""
        d = rec.payload or b""
        where = f"the control record at byte {rec.offset}"
        if not d:
            raise _error(self.path, f"{where} is empty")
        kind = d[0]

        def string(p: int, what: str) -> tuple[str, int]:
            if p + 4 > len(d):
                raise _error(self.path, f"{where} is too short for its {what}'s length")
            (k,) = struct.unpack_from("<I", d, p)
            if p + 4 + k > len(d):
                raise _error(self.path, f"{where} gives its {what} {k} bytes, past the record's end")
            text = d[p + 4 : p + 4 + k]
            if what == "name":  # bad bytes escaped, not replaced: two names never read as one
                return shown_name(text.decode("utf-8", "surrogateescape")), p + 4 + k
            return text.decode("utf-8", "replace"), p + 4 + k

        if kind in (CONTROL_START, CONTROL_FINISH, CONTROL_SET_METADATA) and len(d) < 5:
            raise _error(self.path, f"{where} is too short for its entry id")
        if kind == CONTROL_START:
            (eid,) = struct.unpack_from("<I", d, 1)
            name, p = string(5, "name")
            typ, p = string(p, "type")
            meta, p = string(p, "metadata")
            return kind, Entry(eid, name, typ, meta)
        if kind == CONTROL_FINISH:
            return kind, struct.unpack_from("<I", d, 1)[0]
        if kind == CONTROL_SET_METADATA:
            (eid,) = struct.unpack_from("<I", d, 1)
            meta, _ = string(5, "metadata")
            return kind, (eid, meta)
        raise _error(self.path, f"{where} has an unknown kind {kind} (0-2 are defined)")


def read_wpilog(path, wanted: Callable[[str], bool]) -> tuple[dict[str, Signal], dict[str, Entry], list[str]]:
    """The signals whose entry name `wanted` accepts, every entry the log starts (name -> Entry, the
    last Start of a name), and the reader's warnings. Memory: the kept signals' samples and a
    chunk. Each chunk's records (WPILog.scan) are decoded together with numpy: their entry ids,
    then the headers and payloads of the kept entries' records only, between the control records
    (taken one by one, in file order, so an id finished and started again maps right)."""
    log = WPILog(path)
    live: dict[int, Entry] = {}
    kept: dict[int, Signal] = {}
    out: dict[str, Signal] = {}
    seen: dict[str, Entry] = {}
    parts: dict[str, list] = {}  # name -> [(times, values)] in file order
    for buf, base, starts, whole in log.scan(kept.__contains__):
        if not whole:  # a long record of an entry not kept, skipped unread
            continue
        a = np.frombuffer(buf, np.uint8)
        pos = np.array(starts, dtype=np.int64)
        bits = a[pos]
        il = (bits & 3).astype(np.int64) + 1
        ent = a[pos + 1].astype(np.int64) if int(il.max()) == 1 else _le(a, pos + 1, il).astype(np.int64)
        lo = 0
        for c in [*np.flatnonzero(ent == 0).tolist(), len(pos)]:
            if c > lo and kept:
                _take(log, a, buf, base, pos[lo:c], bits[lo:c], il[lo:c], ent[lo:c], live, kept, parts)
            lo = c + 1
            if c == len(pos):
                break
            kind, what = log.control(_record(buf, base, starts[c]))
            if kind == CONTROL_START:
                live[what.id] = what
                seen[what.name] = what
                kept.pop(what.id, None)
                if wanted(what.name):
                    sig = out.get(what.name)
                    if sig is None:
                        sig = Signal(what.name, what.type, what.metadata)
                        if what.type in ("string", "json"):
                            sig.values = Texts()
                        out[what.name] = sig
                        parts[what.name] = []
                    kept[what.id] = sig
            elif kind == CONTROL_FINISH:
                live.pop(what, None)
                kept.pop(what, None)
            else:
                eid, meta = what
                if eid in live:
                    e = live[eid]
                    live[eid] = seen[e.name] = Entry(e.id, e.name, e.type, meta)
                    if eid in kept:
                        kept[eid].metadata = meta
    for name, sig in out.items():
        _finish(sig, parts.pop(name))
    return out, seen, log.warnings


def _le(a, at, width):
    """Little-endian unsigned integers of `width` bytes (1-8 each) at offsets `at` of the bytes `a`."""
    got = a[at].astype(np.uint64)
    for k in range(1, int(width.max()) if len(width) else 0):
        m = width > k
        if m.all():
            got |= a[at + k].astype(np.uint64) << np.uint64(8 * k)
        else:
            got[m] |= a[at[m] + k].astype(np.uint64) << np.uint64(8 * k)
    return got


def _record(buf: bytes, base: int, p: int) -> Record:
    b = buf[p]
    il, sl, tl = (b & 3) + 1, ((b >> 2) & 3) + 1, ((b >> 4) & 7) + 1
    q = p + 1 + il + sl
    n = int.from_bytes(buf[p + 1 + il : q], "little")
    ts = int.from_bytes(buf[q : q + tl], "little")
    return Record(int.from_bytes(buf[p + 1 : p + 1 + il], "little"), ts, buf[q + tl : q + tl + n], base + p)


def _take(log, a, buf, base, pos, bits, il, ent, live, kept, parts) -> None:
    """The kept entries' records among one run of data records (no control record between them):
    their times and values (datalog.adoc "Data Types": double, float, int64, boolean as numbers,
    string and json as text; arrays, raw and structs are not read) appended to `parts`, each
    signal's in file order. The first bad record in file order (a payload of the wrong size for
    its type, a non-finite number) is refused naming it."""
    by_signal: dict[int, list[int]] = {}
    for eid, sig in kept.items():
        by_signal.setdefault(id(sig), []).append(eid)
    errors = []  # (position in the run, message)
    for ids in by_signal.values():
        sig = kept[ids[0]]
        text = not sig.numeric()
        got = []  # (indices in the run, times, values)
        for eid in ids:
            idx = np.flatnonzero(ent == eid)
            if not len(idx):
                continue
            entry = live[eid]
            typ = entry.type
            if (typ in ("string", "json")) != text or not (text or typ in _DTYPES):
                continue  # not a type read here, or a name started again as another kind
            p, b, w = pos[idx], bits[idx], il[idx]
            sl = ((b >> 2) & 3).astype(np.int64) + 1
            tl = ((b >> 4) & 7).astype(np.int64) + 1
            q = p + 1 + w
            size = _le(a, q, sl).astype(np.int64)
            ts = _le(a, q + sl, tl)
            at = q + sl + tl
            times = ts.astype(np.float64) / 1e6
            if text:
                got.append((idx, times, _text_codes(a, buf, at, size, sig.values)))
                continue
            width = np.dtype(_DTYPES[typ]).itemsize
            wrong = np.flatnonzero(size != width)
            if len(wrong):
                k = int(wrong[0])
                errors.append(
                    (
                        int(idx[k]),
                        f"entry {quoted(entry.name)} ({typ}) has a {int(size[k])}-byte record at byte "
                        f"{base + int(p[k])}; a {typ} is {width} bytes",
                    )
                )
                idx, at, times, ts = idx[:k], at[:k], times[:k], ts[:k]
            raw = a[at[:, None] + np.arange(width)]
            values = (raw[:, 0] != 0).astype(np.float64) if typ == "boolean" else raw.view(_DTYPES[typ])[:, 0]
            values = values.astype(np.float64)
            bad = np.flatnonzero(~np.isfinite(values))
            if len(bad):
                k = int(bad[0])
                errors.append(
                    (
                        int(idx[k]),
                        f"entry {quoted(sig.name)} holds a non-finite value ({float(values[k])}) at "
                        f"t = {int(ts[k]) / 1e6:g} s",
                    )
                )
            got.append((idx, times, values))
        if len(got) == 1:
            parts[sig.name].append(got[0][1:])
        elif got:  # several ids of one name in this run: in file order
            idx = np.concatenate([g[0] for g in got])
            order = np.argsort(idx, kind="stable")
            times = np.concatenate([g[1] for g in got])[order]
            parts[sig.name].append((times, np.concatenate([g[2] for g in got])[order]))
    if errors:
        raise _error(log.path, min(errors)[1])


# A chunk's string records whose payloads are all at most _TEXT_BYTES long are read as words: the
# string's bytes 8 at a time (little-endian, the bytes past its end masked to 0) and its size. The
# records are grouped by a hash of their words, each group's first decoded once, and every record
# checked equal to its group's first, word by word (one that is not, a hash shared by two strings,
# is grouped exactly by numpy's unique of its words).
_TEXT_BYTES = 64
_TEXT_FEW = 32  # fewer records in a chunk: decoded one by one (numpy's calls would cost more)
_MIX = np.array(
    [0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9, 0xD6E8FEB86659FD93, 0xFF51AFD7ED558CCD,
     0xC4CEB9FE1A85EC53, 0x94D049BB133111EB, 0xBF58476D1CE4E5B9, 0x27D4EB2F165667C5],
    np.uint64,
)  # fmt: skip  # odd 64-bit constants (hash mixing), one a word and one for the size
# word j's mask for a string of n bytes (_MASK[j, n]): its bytes 8j.. that are the string's
_MASK = np.array(
    [
        [(1 << (8 * min(max(n - 8 * j, 0), 8))) - 1 for n in range(_TEXT_BYTES + 1)]
        for j in range(_TEXT_BYTES // 8)
    ],
    np.uint64,
)


def _text_codes(a, buf, at, size, texts: Texts) -> np.ndarray:
    """The codes in `texts` of the strings of the records whose payloads are at offsets `at` (sizes
    `size`) of the chunk `buf` (bytes `a`), each decoded as UTF-8 (a bad byte replaced, as before):
    a test state's few distinct values are decoded once a chunk, not once a record."""
    k = len(at)
    if not k:
        return np.zeros(0, np.int32)
    width = int(size.max())
    code = texts.code
    if width > _TEXT_BYTES or k < _TEXT_FEW:  # free text (a json entry), or a few: one decode a record
        return np.fromiter(
            (code(buf[s : s + n].decode("utf-8", "replace")) for s, n in zip(at.tolist(), size.tolist())),
            np.int32,
            k,
        )
    n_words = (width + 7) // 8
    if int(at.max()) + 8 * n_words > len(a):  # a word read past the chunk's end
        a = np.concatenate((a, np.zeros(8 * n_words, np.uint8)))
    # the 8 bytes from every byte offset, as one little-endian word (a view, nothing copied)
    word_at = np.ndarray((len(a) - 7,), dtype="<u8", buffer=a, strides=(1,))
    words = [word_at[at + 8 * j] & _MASK[j][size] for j in range(n_words)]
    hashes = size.astype(np.uint64) * _MIX[-1]
    for j, w in enumerate(words):
        hashes += w * _MIX[j]  # wraps: a hash, checked below
    distinct = np.unique(hashes)
    group = np.searchsorted(distinct, hashes)
    first = np.empty(len(distinct), np.intp)
    first[group] = np.arange(k)  # a record of each group (any: all are checked against it)
    lead = first[group]
    same = size == size[lead]
    for w in words:
        same &= w == w[lead]
    got = np.array(
        [
            code(buf[s : s + n].decode("utf-8", "replace"))
            for s, n in zip(at[first].tolist(), size[first].tolist())
        ],
        np.int32,
    )
    codes = got[group]
    if not same.all():  # a hash shared by two strings: those records grouped exactly
        rest = np.flatnonzero(~same)
        exact = np.column_stack([size[rest].astype(np.uint64), *(w[rest] for w in words)])
        _, one, back = np.unique(exact, axis=0, return_index=True, return_inverse=True)
        r = rest[one]
        again = np.array(
            [
                code(buf[s : s + n].decode("utf-8", "replace"))
                for s, n in zip(at[r].tolist(), size[r].tolist())
            ],
            np.int32,
        )
        codes[rest] = again[back.ravel()]
    return codes


def _finish(sig: Signal, got: list) -> None:
    """A signal's samples from its parts, sorted by time (stably) when the file had them out of order."""
    if not got:
        return
    times = np.concatenate([g[0] for g in got])
    text = not sig.numeric()
    values = np.concatenate([g[1] for g in got])
    got.clear()  # the parts go before the copies below are made (a third less at the peak)
    if len(times) > 1 and bool(np.any(times[1:] < times[:-1])):
        order = np.argsort(times, kind="stable")  # equal times keep the file's order
        times = times[order]
        values = values[order]
        sig.reordered = True
    sig.times = array("d")  # filled from numpy's buffer, not from a copy of it in bytes
    sig.times.frombytes(memoryview(np.ascontiguousarray(times)).cast("B"))
    if text:
        sig.values.codes = values
    else:
        sig.values = array("d")
        sig.values.frombytes(memoryview(np.ascontiguousarray(values, dtype=np.float64)).cast("B"))


def _sort(sig: Signal) -> None:
    t = sig.times
    if all(t[i] <= t[i + 1] for i in range(len(t) - 1)):
        return
    order = sorted(range(len(t)), key=t.__getitem__)  # stable: equal times keep the file's order
    sig.times = array("d", (t[i] for i in order))
    v = sig.values
    if isinstance(v, array):
        sig.values = array("d", (v[i] for i in order))
    else:
        sig.values = Texts(v.codes[np.array(order, dtype=np.int64)], v.table)
    sig.reordered = True


def _number(text: str) -> float:
    """A CSV cell's number (_NUMBER), or ValueError."""
    text = text.strip()
    if not _NUMBER.fullmatch(text):
        raise ValueError(text)
    return float(text)


def is_number(text: str) -> bool:
    """Whether a CSV cell reads as a number (_NUMBER)."""
    return _NUMBER.fullmatch(text.strip()) is not None


def _lines(f, path):
    """The file's lines, each at most CSV_LINE characters (memory stays bounded on a file that
    never ends a line)."""
    while True:
        line = f.readline(CSV_LINE)
        if not line:
            return
        if len(line) >= CSV_LINE and not line.endswith(("\n", "\r")):
            raise _error(path, f"has a line longer than {CSV_LINE >> 20} MiB; not a log CSV")
        yield line


def read_csv(path, wanted: Callable[[str], bool]) -> tuple[dict[str, Signal], dict[str, Entry], list[str]]:
    """AdvantageScope's CSV export: the first column the time in seconds, then one column per
    signal; an empty cell is no sample. A column whose every cell is a number is numeric, else text
    (a test state). Read row by row, keeping only the wanted columns."""
    path = os.fspath(path)
    try:
        f = _open(path, newline="", encoding="utf-8-sig")
    except OSError as exc:
        raise _error(path, f"cannot be read ({exc.strerror or exc})") from None
    with f:
        rows = csv.reader(_lines(f, path))
        try:
            header = next(rows, None)
            if not header or header[0].strip().lower() not in TIME_COLUMNS:
                raise _error(path, "is not a log CSV: its first column must be the time ('Timestamp', in s)")
            names = [shown_name(h.strip()) for h in header]  # as a WPILog's (invisible ones escaped)
            cols = [i for i in range(1, len(names)) if wanted(names[i])]
            first: dict[str, int] = {}
            for i in cols:  # two columns of one name: which one is meant is not known
                if names[i] in first:
                    raise _error(
                        path,
                        f"has two columns named {quoted(names[i])} (columns {first[names[i]] + 1} and {i + 1})",
                    )
                first[names[i]] = i
            cells: dict[int, tuple[array, list]] = {i: (array("d"), []) for i in cols}
            for line, row in enumerate(rows, start=2):
                if not row:
                    continue
                try:
                    t = _number(row[0])
                except ValueError:
                    raise _error(path, f"line {line}: the time {row[0]!r} is not a number") from None
                if not math.isfinite(t):
                    raise _error(path, f"line {line}: the time is {row[0]!r}, not a finite number")
                for i in cols:
                    if i < len(row) and row[i].strip():
                        cells[i][0].append(t)
                        cells[i][1].append(row[i].strip())
        except (csv.Error, UnicodeDecodeError) as exc:
            raise _error(path, f"is not a readable CSV ({exc})") from None
    out: dict[str, Signal] = {}
    for i in cols:
        times, text = cells[i]
        try:
            values: array | Texts = array("d", (_number(s) for s in text))
        except ValueError:
            values = Texts.of(text)
        sig = Signal(names[i], "double" if isinstance(values, array) else "string", "", times, values)
        if isinstance(values, array):
            bad = next((k for k, v in enumerate(values) if not math.isfinite(v)), None)
            if bad is not None:
                raise _error(
                    path,
                    f"column {quoted(names[i])} holds a non-finite value ({text[bad]}) at t = {times[bad]:g} s",
                )
        _sort(sig)
        out[names[i]] = sig
    entries = {n: Entry(k, n, "", "") for k, n in enumerate(names[1:], start=1)}
    return out, entries, []


def read(path, wanted: Callable[[str], bool]) -> tuple[dict[str, Signal], dict[str, Entry], list[str]]:
    """A .csv file as AdvantageScope's export, anything else as a WPILog."""
    if os.fspath(path).lower().endswith(".csv"):
        return read_csv(path, wanted)
    return read_wpilog(path, wanted)
