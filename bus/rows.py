"""Rows of neutral lists on the bus: their check, and packed rows (docs/bus.md, "Packed rows").

The rows of `Percepts.percepts` and `Beliefs.beliefs` travel each as a msgpack bin holding that
row's own msgpack bytes (a reader also takes plain arrays, and a mix). A reader decodes a row
whose bytes equal one of the last message's on the same key to that very list, without reading
it again; nobody mutates a decoded row, so the engine takes a row it has seen as unchanged
(agents/lang/inference/shared_rows.py). A writer packs a row that is the same object as one it sent
last
time in the same field to the same bytes without packing it again. Every check failure raises
TypeError naming the row; the codec turns it into a CodecError naming the key and field.
"""

from __future__ import annotations

import threading
from itertools import chain, compress, repeat
from math import isfinite
from operator import is_, itemgetter, ne
from typing import Any

import msgpack

from bus.schema import brief

_ATOM_TYPES = frozenset({str, int, float})  # exact types: bool and None are refused
_LIST_ONLY = frozenset({list})
_STR_ONLY = frozenset({str})
_local = threading.local()  # per thread: a Packer, and the rows sent and seen per slot or key


def as_array(v: Any) -> list:
    """``v`` if it is a list (a msgpack array), else TypeError saying what it is."""
    if not isinstance(v, list):
        raise TypeError(f"expected array, got {type(v).__name__}")
    return v


def packer() -> msgpack.Packer:
    """This thread's Packer (autoreset: each `pack` returns the bytes of one object and
    leaves the packer empty, also after an error)."""
    packer = getattr(_local, "packer", None)
    if packer is None:
        packer = _local.packer = msgpack.Packer(use_bin_type=True, autoreset=True)
    return packer


def check_rows(v: Any) -> tuple:
    """A tuple of neutral-form lists, each a name (a str) and then items that are str, int or
    float (never bool/None), floats finite (NaN and infinities would poison every comparison
    downstream): ``["self", "ME", "speed", 20.0]``, ``["*gas", 6.25]``.

    Checked in C-level passes over the types, the first items and the floats; only a bad
    payload takes the row-by-row loop that names the offending row.
    """
    rows = as_array(v)
    if _LIST_ONLY.issuperset(map(type, rows)) and all(rows):
        atoms = list(chain.from_iterable(rows))
        types = list(map(type, atoms))
        if _ATOM_TYPES.issuperset(types) and \
                _STR_ONLY.issuperset(map(type, map(itemgetter(0), rows))) and \
                all(map(isfinite, compress(atoms, map(is_, types, repeat(float))))):
            return tuple(rows)
    atoms_only = _ATOM_TYPES.issuperset
    for row in rows:
        if type(row) is not list or not atoms_only(map(type, row)):
            raise TypeError(f"expected arrays of str, int or float, found item {brief(row)}")
        if not row or type(row[0]) is not str:
            raise TypeError(f"expected arrays [name, value, ...] with a name first, found item "
                            f"{brief(row)}")
        bad = [a for a in row if type(a) is float and not isfinite(a)]
        if bad:
            raise TypeError(f"expected finite numbers, found {bad[0]} in item {brief(row)}")
    raise TypeError("expected arrays of str, int or float")  # not reached: some row failed


def pack_rows(rows: Any, slot: tuple) -> list[bytes]:
    """Each row as its own msgpack bytes; a row sent last time in ``slot`` as the same object
    keeps its bytes (rows are never mutated once sent)."""
    sent = getattr(_local, "sent", None)
    if sent is None:
        sent = _local.sent = {}
    last = sent.get(slot)
    pack = packer().pack
    ids = list(map(id, rows))
    if last:
        out = [h[1] if h is not None and h[0] is r else pack(r)
               for h, r in zip(map(last.get, ids), rows, strict=True)]
    else:
        out = list(map(pack, rows))
    sent[slot] = dict(zip(ids, zip(rows, out, strict=True), strict=True))
    return out


def shared_rows(kind: str, agent: str, rows: Any) -> tuple:
    """``rows`` as a receiver of the packed field would get them, for a message handed over in
    memory (agents/processes/shared.py): each row whose bytes equal those of a row last given
    here for (``kind``, ``agent``) is replaced by that row. Encoding the message afterwards
    packs no row again."""
    memo = getattr(_local, "interned", None)
    if memo is None:
        memo = _local.interned = {}
    slot = (kind, agent)
    last = memo.get(slot, {})
    data = pack_rows(rows, slot)
    out = tuple(last.get(b, r) for b, r in zip(data, rows, strict=True))
    memo[slot] = dict(zip(data, out, strict=True))
    _local.sent[slot] = dict(zip(map(id, out), zip(out, data, strict=True), strict=True))
    return out


def unpack_rows(key: str, v: Any) -> tuple:
    """The rows of a packed field received on ``key``, checked as ``check_rows`` checks them; a
    row of the same bytes as one in the last message on ``key`` is that message's list.

    Kept per key: the last message's items and rows, and bytes -> row of the rows seen lately
    (rebuilt when it holds twice as many as a message). Items are first compared position by
    position with the last message's (rows mostly stay where they were), then looked up."""
    items = as_array(v)
    seen = getattr(_local, "seen", None)
    if seen is None:
        seen = _local.seen = {}
    was = seen.get(key)
    if was is not None and was[0] == items:  # the very same bytes: last message's tuple
        return was[1]
    n = len(items)
    by: dict = was[2] if was is not None else {}
    at = list(compress(range(n), map(ne, items, was[0]))) \
        if was is not None and was[0] is not None and len(was[0]) == n else None
    if at is not None and len(at) * 4 <= n:  # a few rows changed: look only those up
        got = list(was[1])
        for i in at:
            b = items[i]
            got[i] = by.get(b) if type(b) is bytes else None
        new = [i for i in at if got[i] is None]
    else:
        got = _known(by, items)
        new = list(compress(range(n), map(is_, got, repeat(None))))
    if new:
        fresh = check_rows(_unpacked_all([items[i] for i in new]))
        for i, row in zip(new, fresh, strict=True):
            got[i] = row
        if len(new) * 4 <= n:
            by.update((items[i], got[i]) for i in new if type(items[i]) is bytes)
        else:
            by = _by_bytes(items, got)
    if len(by) > 2 * n + 16:
        by = _by_bytes(items, got)
    out = tuple(got)
    # only bytes compare strictly: [3] == [3.0], so plain arrays are never matched by position
    seen[key] = (items if _BYTES_ONLY.issuperset(map(type, items)) else None, out, by)
    return out


def _by_bytes(items: list, rows: list) -> dict:
    """bytes -> row, for the items given as bytes (plain arrays are left out)."""
    try:
        return dict(zip(items, rows, strict=True))
    except TypeError:  # a plain array among the items (unhashable)
        return {b: r for b, r in zip(items, rows, strict=True) if type(b) is bytes}


def _known(last: dict, items: list) -> list:
    """The row in ``last`` of each item given as bytes, else None."""
    try:
        return list(map(last.get, items))
    except TypeError:  # a plain array among the items (unhashable)
        return [last.get(b) if type(b) is bytes else None for b in items]


_BYTES_ONLY = frozenset({bytes})


def _unpacked_all(items: list) -> list:
    """``_unpacked`` of each item: one C-level pass when they are all bytes and all good."""
    if _BYTES_ONLY.issuperset(map(type, items)):
        try:
            return list(map(msgpack.unpackb, items))
        except (ValueError, TypeError, msgpack.UnpackException):
            pass  # name the bad row below
    return list(map(_unpacked, items))


def _unpacked(item: Any) -> Any:
    """One row of a packed field: its own msgpack bytes read, or a plain array as it is."""
    if type(item) is not bytes:
        return item
    try:
        return msgpack.unpackb(item, raw=False, strict_map_key=True)
    except (ValueError, TypeError, msgpack.UnpackException) as exc:
        raise TypeError(f"malformed packed row ({len(item)} bytes): {exc}") from exc


def unpacked_rows(v: Any) -> Any:
    """A packed field's rows as plain arrays (records, tools); anything else as it is."""
    return [_unpacked(r) for r in v] if isinstance(v, list) else v
