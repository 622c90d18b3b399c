"""Reading the robot's logs: WPILib's WPILog (allwpilib datalog/doc/datalog.adoc, version 1.0) and
AdvantageScope's CSV export (a timestamp column, then one column per signal).

Our own streaming reader of the documented format, not robotpy's wpiutil.log.DataLogReader: robotpy
is ~30 MB of native wheels the default install does not have, and its reader maps the whole file;
this one reads 256 KiB at a time and skips the payloads of entries nobody asked for, so memory is set
by the signals kept, not by the log's size (the tests check it against DataLogReader, record by record).

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
import struct
from array import array
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

from ..errors import InputError

CHUNK = 1 << 18  # bytes read at a time: 256 KiB (the peak memory is about three of them)
MAGIC = b"WPILOG"
CONTROL_START, CONTROL_FINISH, CONTROL_SET_METADATA = 0, 1, 2
_FIXED = {"double": ("<d", 8), "float": ("<f", 4), "int64": ("<q", 8), "boolean": ("<?", 1)}
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


@dataclass
class Signal:
    """One entry's samples, sorted by time: numbers (an array of float) or strings (a list)."""

    name: str
    type: str
    metadata: str
    times: array = field(default_factory=lambda: array("d"))  # s
    values: array | list = field(default_factory=lambda: array("d"))
    reordered: bool = False  # its records were not in time order (sorted here)

    def numeric(self) -> bool:
        return isinstance(self.values, array)


def _error(path, message: str) -> InputError:
    return InputError("log", message, os.fspath(path))


class WPILog:
    """A WPILog file opened for streaming: the header is checked here, records are read lazily."""

    def __init__(self, path):
        self.path = os.fspath(path)
        self.warnings: list[str] = []
        try:
            self.size = os.path.getsize(self.path)
            with open(self.path, "rb") as f:
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
        """Every record in file order (L2). A data record whose entry is not in `keep` (a set or
        dict of ids; None: keep all) has no payload read; it is yielded without one when `skipped`,
        else not at all. A record cut off by the end of the file ends the reading with a warning (a
        robot that lost power mid-write leaves one)."""
        path, size = self.path, self.size
        with open(path, "rb") as f:
            f.seek(self.start)
            buf = b""
            pos = 0
            base = self.start  # file offset of buf[0]
            while True:
                if len(buf) - pos < 13:  # the longest header is 1 + 4 + 4 + 8 bytes: top up
                    buf = buf[pos:] + f.read(CHUNK)
                    base += pos
                    pos = 0
                    if not buf:
                        return
                b = buf[pos]
                il, sl, tl = (b & 3) + 1, ((b >> 2) & 3) + 1, ((b >> 4) & 7) + 1
                hl = 1 + il + sl + tl
                if len(buf) - pos < hl:
                    self.warnings.append(
                        f"{path}: ends in a partial record at byte {base + pos}; read up to it"
                    )
                    return
                p = pos + 1
                entry = buf[p] if il == 1 else int.from_bytes(buf[p : p + il], "little")
                p += il
                n = buf[p] if sl == 1 else int.from_bytes(buf[p : p + sl], "little")
                p += sl
                ts = int.from_bytes(buf[p : p + tl], "little")
                p += tl
                offset = base + pos
                end = offset + hl + n
                if end > size:
                    self.warnings.append(
                        f"{path}: ends in a partial record at byte {offset} (its {n}-byte payload runs past "
                        f"the end of the file); read up to it"
                    )
                    return
                if entry != 0 and keep is not None and entry not in keep:
                    if p + n <= len(buf):
                        pos = p + n
                    else:  # the payload runs past what is read: skip it in the file
                        f.seek(end)
                        buf, pos, base = b"", 0, end
                    if skipped:
                        yield Record(entry, ts, None, offset)
                    continue
                if p + n > len(buf):
                    buf = buf[p:] + f.read(max(CHUNK, n - (len(buf) - p)))
                    base += p
                    p = 0
                yield Record(entry, ts, bytes(buf[p : p + n]), offset)
                pos = p + n

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
            return d[p + 4 : p + 4 + k].decode("utf-8", "replace"), p + 4 + k

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


def decode(path, entry: Entry, rec: Record):
    """A data record's value for the entry's type (datalog.adoc "Data Types"), or None for a type
    not read here (arrays, raw, structs)."""
    d = rec.payload or b""
    if entry.type in _FIXED:
        fmt, size = _FIXED[entry.type]
        if len(d) != size:
            raise _error(
                path,
                f"entry {entry.name!r} ({entry.type}) has a {len(d)}-byte record at byte {rec.offset}; "
                f"a {entry.type} is {size} bytes",
            )
        return float(struct.unpack(fmt, d)[0])
    if entry.type in ("string", "json"):
        return d.decode("utf-8", "replace")
    return None


def read_wpilog(path, wanted: Callable[[str], bool]) -> tuple[dict[str, Signal], dict[str, Entry], list[str]]:
    """The signals whose entry name `wanted` accepts, every entry the log starts (name -> Entry, the
    last Start of a name), and the reader's warnings. Memory: the kept signals' samples only."""
    log = WPILog(path)
    live: dict[int, Entry] = {}
    kept: dict[int, Signal] = {}
    out: dict[str, Signal] = {}
    seen: dict[str, Entry] = {}
    for rec in log.records(keep=kept, skipped=False):
        if rec.entry == 0:
            kind, what = log.control(rec)
            if kind == CONTROL_START:
                live[what.id] = what
                seen[what.name] = what
                kept.pop(what.id, None)
                if wanted(what.name):
                    sig = out.get(what.name)
                    if sig is None:
                        sig = Signal(what.name, what.type, what.metadata)
                        if what.type in ("string", "json"):
                            sig.values = []
                        out[what.name] = sig
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
            continue
        sig = kept.get(rec.entry)
        if sig is None:
            continue
        value = decode(path, live[rec.entry], rec)
        if value is None:
            continue
        if isinstance(value, float) and not math.isfinite(value):
            raise _error(
                path,
                f"entry {sig.name!r} holds a non-finite value ({value}) at t = {rec.timestamp / 1e6:g} s",
            )
        sig.times.append(rec.timestamp / 1e6)
        sig.values.append(value)
    for sig in out.values():
        _sort(sig)
    return out, seen, log.warnings


def _sort(sig: Signal) -> None:
    t = sig.times
    if all(t[i] <= t[i + 1] for i in range(len(t) - 1)):
        return
    order = sorted(range(len(t)), key=t.__getitem__)  # stable: equal times keep the file's order
    sig.times = array("d", (t[i] for i in order))
    v = sig.values
    sig.values = array("d", (v[i] for i in order)) if isinstance(v, array) else [v[i] for i in order]
    sig.reordered = True


def read_csv(path, wanted: Callable[[str], bool]) -> tuple[dict[str, Signal], dict[str, Entry], list[str]]:
    """AdvantageScope's CSV export: the first column the time in seconds, then one column per
    signal; an empty cell is no sample. A column whose every cell is a number is numeric, else text
    (a test state). Read row by row, keeping only the wanted columns."""
    path = os.fspath(path)
    try:
        f = open(path, newline="", encoding="utf-8-sig")
    except OSError as exc:
        raise _error(path, f"cannot be read ({exc.strerror or exc})") from None
    with f:
        rows = csv.reader(f)
        try:
            header = next(rows, None)
            if not header or header[0].strip().lower() not in TIME_COLUMNS:
                raise _error(path, "is not a log CSV: its first column must be the time ('Timestamp', in s)")
            names = [h.strip() for h in header]
            cols = [i for i in range(1, len(names)) if wanted(names[i])]
            cells: dict[int, tuple[array, list]] = {i: (array("d"), []) for i in cols}
            for line, row in enumerate(rows, start=2):
                if not row:
                    continue
                try:
                    t = float(row[0])
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
            values: array | list = array("d", (float(s) for s in text))
        except ValueError:
            values = text
        sig = Signal(names[i], "double" if isinstance(values, array) else "string", "", times, values)
        if isinstance(values, array):
            bad = next((k for k, v in enumerate(values) if not math.isfinite(v)), None)
            if bad is not None:
                raise _error(
                    path,
                    f"column {names[i]!r} holds a non-finite value ({text[bad]}) at t = {times[bad]:g} s",
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
