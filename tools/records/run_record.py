"""Run records: every launch and simulate writes `record.mcap` in its run folder, the source of
`teleo explain`, `teleo plot`, `teleo replay` and the web view (docs/records.md).

MCAP (mcap.dev), zstd-compressed chunks, one channel per bus key (topic = the key), each
message the JSON record of bus/record.py with a JSON Schema per kind, so Foxglove decodes it.
Log time is the world time of the message's cycle [s -> ns]; publish time is when it was sent
(wall clock [ns]). Metadata `teleo.run` holds the run id and where it came from, and
`teleo.goals` each agent's goal history (status changes of every goal), for summaries.

    with RecordWriter(path, run, {"source": "launch"}) as rec:
        rec.add(key, record)                 # a record from bus.record.to_record
    record = RunRecord(locate("driving-demo-ab12cd"))
    record.by_cycle("intention", "ME")[213]  # the intention record of cycle 213
"""

from __future__ import annotations

import json
import logging
import struct
from collections import defaultdict
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

import orjson
from mcap.exceptions import McapError
from mcap.reader import NonSeekingReader, make_reader
from mcap.well_known import MessageEncoding, SchemaEncoding
from mcap.writer import CompressionType, Writer

from bus import keys
from bus.record import json_schema
from tools.records.goal_history import GoalHistory
from tools.runs import runfile
from world.static import has_static

log = logging.getLogger(__name__)
RECORD_FILE = "record.mcap"
MCAP_MAGIC = b"\x89MCAP0\r\n"
RUN_META = "teleo.run"
GOALS_META = "teleo.goals"
GOAL_HISTORY = "goal-history.json"  # a launch without a record: its goal histories
                                    # (tools/records/goal_watch.py)
STATE_RANGES = "world_state_cycles"  # in RUN_META: [[first, last], ...] of the states held
_KEEP_TIMES = 4096  # cycles whose world time is remembered (a forever run must not grow)
_MAX_NS = 2**64 - 1  # the largest time an MCAP record holds [ns]


class RecordError(Exception):
    """A run record that cannot be found or read; the message names the file and why."""


def cycle_ranges(cycles: Iterable[int]) -> list[list[int]]:
    """[[first, last], ...] (inclusive) of a set of cycles, in order."""
    out: list[list[int]] = []
    for c in sorted(set(cycles)):
        if out and c == out[-1][1] + 1:
            out[-1][1] = c
        else:
            out.append([c, c])
    return out


class RecordWriter:
    """Writes one run record. Records of a cycle whose world state has not been seen yet are
    held until it arrives (their log time is that state's world time)."""

    def __init__(self, path: Path, run: str, meta: dict[str, str] | None = None) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        self.path = path
        self._file = path.open("wb")
        self._mcap = Writer(self._file, compression=CompressionType.ZSTD)
        self._mcap.start(profile="", library="teleo")
        self._meta = {"run": run, **(meta or {})}
        self._schemas: dict[str, int] = {}
        self._channels: dict[str, int] = {}
        self._times: dict[int, int] = {}  # cycle -> world time [ns]
        self._pending: dict[int, list[tuple[str, dict[str, Any], int]]] = defaultdict(list)
        self.history = GoalHistory()
        self._extra_meta: dict[str, dict[str, str]] = {}
        self.messages = 0
        self.cycles = 0
        self._states: set[int] = set()  # the cycles whose world state is in the record
        self._closed = False

    def __enter__(self) -> RecordWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def add(self, key: str, record: dict[str, Any], publish_ns: int | None = None) -> None:
        """Add one record received (or produced) on `key`."""
        env = record["env"]
        cycle, sent = int(env["cycle"]), int(env["sent_ns"] if publish_ns is None else publish_ns)
        if record["kind"] == "WorldState":
            self._times[cycle] = round(float(record["snapshot"].get("time", 0.0)) * 1e9)
            self.cycles = max(self.cycles, cycle + 1)
            self._states.add(cycle)
            self._write(key, record, self._times[cycle], sent)
            for k, r, s in self._pending.pop(cycle, ()):
                self._write(k, r, self._times[cycle], s)
            if len(self._times) > _KEEP_TIMES:
                del self._times[min(self._times)]
        elif cycle in self._times:
            self._write(key, record, self._times[cycle], sent)
        elif cycle < 0:   # outside the cycle (the world's static part: world/static)
            self._write(key, record, self._latest(), sent)
        else:
            self._pending[cycle].append((key, record, sent))

    def meta(self, name: str, data: dict[str, str]) -> None:
        """Add a metadata record (written when the record closes)."""
        self._extra_meta[name] = dict(data)

    def _latest(self) -> int:
        return self._times[max(self._times)] if self._times else 0

    def _estimate(self, cycle: int) -> int:
        """The world time of a cycle never seen: extrapolated with the last step [ns]."""
        known = sorted(self._times)[-2:]
        if not known:
            return 0
        step = (self._times[known[1]] - self._times[known[0]]) // (known[1] - known[0]) \
            if len(known) == 2 else 0
        return self._times[known[-1]] + (cycle - known[-1]) * step

    def _write(self, key: str, record: dict[str, Any], log_ns: int, sent_ns: int) -> None:
        channel = self._channels.get(key)
        if channel is None:
            channel = self._channels[key] = self._mcap.register_channel(
                topic=key, message_encoding=MessageEncoding.JSON,
                schema_id=self._schema(record["kind"]))
        if record["kind"] in ("Intention", "GoalList"):
            self.history.feed(record, self._states.__contains__)
        self._mcap.add_message(channel_id=channel, log_time=_stamp(log_ns),
                               data=orjson.dumps(record), publish_time=_stamp(sent_ns))
        self.messages += 1

    def _schema(self, kind: str) -> int:
        if kind not in self._schemas:
            self._schemas[kind] = self._mcap.register_schema(
                name=f"teleo.{kind}", encoding=SchemaEncoding.JSONSchema,
                data=json.dumps(json_schema(kind)).encode())
        return self._schemas[kind]

    def close(self) -> None:
        """Write what is held, the metadata and the summary section; close the file."""
        if self._closed:
            return
        self._closed = True
        for cycle in sorted(self._pending):
            for k, r, s in self._pending[cycle]:
                self._write(k, r, self._estimate(cycle), s)
        self._pending.clear()
        self._mcap.add_metadata(RUN_META, {**self._meta, "cycles": str(self.cycles),
                                           "world_states": str(len(self._states)),
                                           STATE_RANGES: json.dumps(cycle_ranges(self._states))})
        self._mcap.add_metadata(GOALS_META, self.history.to_meta())
        for name, data in self._extra_meta.items():
            self._mcap.add_metadata(name, data)
        self._mcap.finish()
        self._file.close()


def _stamp(ns: int) -> int:
    """A time an MCAP record can hold (unsigned 64 bits [ns]): a spoilt message's cycle or
    send time far out of range is recorded at the nearest end, not left to fail the close."""
    return min(max(0, ns), _MAX_NS)


def locate(run: str | Path) -> Path:
    """The record of RUN: an .mcap file, a run folder holding record.mcap, or a run id under
    the runs folder ($TELEO_RUN_DIR/runs, default out/runs). Raises RecordError."""
    path = Path(run)
    candidates = list(dict.fromkeys([path, path / RECORD_FILE,
                                     runfile.base_dir() / "runs" / str(run) / RECORD_FILE]))
    for c in candidates:
        if c.is_file():
            return c
    runs = runfile.base_dir() / "runs"
    known = sorted((p for p in runs.iterdir() if (p / RECORD_FILE).is_file()),
                   key=lambda p: (p / RECORD_FILE).stat().st_mtime, reverse=True) \
        if runs.is_dir() else []
    more = f" and {len(known) - 5} older" if len(known) > 5 else ""
    hint = f"; runs with a record in {runs}, newest first: " \
        f"{', '.join(p.name for p in known[:5])}{more}" if known else \
        f"; no run in {runs} has a record"
    raise RecordError(f"{run}: no run record here (looked for "
                      f"{', '.join(str(c) for c in candidates)}){hint}")


class RunRecord:
    """A run record opened for reading (the whole file is read once, lazily). Its world
    states are whole: the world's static part, held once (world/static), is put back into
    each; ``raw``: as they were sent (a replay sends them so again)."""

    def __init__(self, path: Path, raw: bool = False) -> None:
        self.path = Path(path)
        self.raw = raw
        self._records: list[tuple[str, dict[str, Any]]] | None = None
        self.meta: dict[str, dict[str, str]] = {}
        self.truncated = False  # never closed (its writer was killed): read as far as it goes
        try:
            with self.path.open("rb") as f:
                if f.read(len(MCAP_MAGIC)) != MCAP_MAGIC:
                    raise RecordError(f"{self.path}: not a readable run record (not MCAP)")
                f.seek(0)
                try:
                    self.meta = {m.name: dict(m.metadata)
                                 for m in make_reader(f).iter_metadata()}
                except (McapError, ValueError, OSError, struct.error) as exc:  # too short
                    self.truncated = True
                    log.warning("%s: no summary section (%s); reading it as far as it goes",
                                self.path, exc)
        except OSError as exc:
            raise RecordError(f"{self.path}: not a readable run record ({exc})") from exc

    @property
    def run(self) -> str:
        return self.meta.get(RUN_META, {}).get("run", self.path.parent.name)

    def records(self) -> list[tuple[str, dict[str, Any]]]:
        """Every (key, record) in log-time order (within a cycle, in the order written)."""
        if self._records is None:
            self._records = []
            try:
                with self.path.open("rb") as f:
                    reader = NonSeekingReader(f) if self.truncated else make_reader(f)
                    for _, ch, msg in reader.iter_messages(log_time_order=not self.truncated):
                        self._records.append((ch.topic, orjson.loads(msg.data)))
            except (McapError, ValueError, struct.error, orjson.JSONDecodeError) as exc:
                if not self.truncated:  # struct.error: a record cut inside a header
                    raise RecordError(f"{self.path}: cannot read its messages ({exc})") from exc
            except OSError as exc:
                raise RecordError(f"{self.path}: cannot read its messages ({exc})") from exc
            if not self.raw:
                _put_static_back(self._records)
        return self._records

    def kinds(self, kind: str) -> Iterator[tuple[str, dict[str, Any]]]:
        """Records whose key is of `kind` (keys.kind_of_key: "percepts", "intention", ...)."""
        for key, rec in self.records():
            if key.rsplit("/", 1)[-1] == kind or _stats_kind(key) == kind:
                yield key, rec

    def kinds_of(self, kinds: tuple[str, ...], agent: str | None = None
                 ) -> Iterator[tuple[str, dict[str, Any]]]:
        """Records of any of `kinds` (of `agent`), in the record's order."""
        for key, rec in self.records():
            if key.rsplit("/", 1)[-1] in kinds and (agent is None
                                                     or keys.agent_of_key(key) == agent):
                yield key, rec

    def agents(self) -> list[str]:
        return sorted({a for key, _ in self.records() if (a := keys.agent_of_key(key))})

    def by_cycle(self, kind: str, agent: str | None = None) -> dict[int, dict[str, Any]]:
        """cycle -> the record of `kind` (for `agent`) of that cycle (the last one if several)."""
        return {rec["env"]["cycle"]: rec for key, rec in self.kinds(kind)
                if agent is None or keys.agent_of_key(key) == agent}

    def state_cycles(self) -> set[int]:
        """The cycles whose world state the record holds (from its metadata when it says)."""
        ranges = self.meta.get(RUN_META, {}).get(STATE_RANGES)
        if ranges is not None:
            return {c for first, last in json.loads(ranges) for c in range(first, last + 1)}
        return {rec["env"]["cycle"] for _, rec in self.kinds("state")
                if rec.get("kind") == "WorldState"}

    def held_ranges(self) -> list[list[int]]:
        """cycle_ranges of the world states held: from the metadata, else (a record never
        closed, or written before it said) from the records themselves."""
        ranges = self.meta.get(RUN_META, {}).get(STATE_RANGES)
        return json.loads(ranges) if ranges is not None else cycle_ranges(self.state_cycles())

    def goal_history(self) -> dict[str, dict[str, list[dict[str, Any]]]]:
        """agent -> goal id -> status changes (from the metadata, else from the intentions;
        a change seen after a gap says so: GoalHistory)."""
        meta = self.meta.get(GOALS_META)
        if meta is not None:
            return {agent: json.loads(text) for agent, text in meta.items()}
        history, states = GoalHistory(), self.state_cycles()
        for _, rec in self.kinds_of(("intention", "goal-list")):
            history.feed(rec, states.__contains__)
        return dict(history.changes)


def _put_static_back(records: list[tuple[str, dict[str, Any]]]) -> None:
    """Each world state of a record with the world's static part it holds once (the first
    WorldStatic; world/static.py); a state that has it (an older record) is left as it is."""
    told = next((rec.get("static") for _, rec in records if rec.get("kind") == "WorldStatic"),
                None)
    if not isinstance(told, dict) or not told:
        return
    for _, rec in records:
        snap = rec.get("snapshot") if rec.get("kind") == "WorldState" else None
        if isinstance(snap, dict) and not has_static(snap):
            rec["snapshot"] = {**told, **snap}


def _stats_kind(key: str) -> str:
    parts = key.split("/")
    return "stats" if len(parts) >= 3 and parts[2] == "stats" else ""
