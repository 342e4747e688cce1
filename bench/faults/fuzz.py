"""Fuzz drill of teleo's readers (issues 11 and 24; fault drill 4): any input gives teleo's own
refusal, naming the field (or file:line:col), and never a crash or a hang.

    .venv/bin/python bench/faults/fuzz.py [--n 100000] [--seed 1] [--reader NAME ...] [--out DIR]
                                   [--limit 5]

For each reader it feeds N inputs: the drill's minimal cases first, then mutations of real
inputs (the repository's programs and percept files, goals, world events, every bus message
of a real in-process pipeline) and generated extremes (wrong types in every field, deep
nesting, huge numbers, NaN, unhashable lists and maps, bytes that are not UTF-8). An input
is *accepted*, or *refused* with the reader's own error (ProgramError, GoalError, a click
error, CodecError, the bus's Refused, a failed outcome, or a goal reply with ok false);
anything else is a *crash*, and an input that takes longer than --limit seconds a *hang*.
A refusal must name a field of the input (or the payload as a whole: "malformed msgpack"),
or file:line:col for texts; one that does not is counted *unnamed*. Printed per reader:
inputs, accepted, refused, crashes, hangs, unnamed, and the median, p99 and max time of an
input; the exit status is 1 on any crash, hang or unnamed refusal. With --out, each crashing
input is written there to replay.

The readers of texts: program (bytes -> decode_text -> load_program_text), percepts (bytes ->
decode_text -> parse_percepts), goal (parse_goal against programs/driving.tlp), event (the
JSON argument of `teleo event`), scenario (bytes -> a scenario file, read and checked fully
as `teleo launch` does), request (bytes -> bus.codec.decode -> the goal-entry
process's answer, with the scenarios/driving_demo.toml agents and a real store file). The
bus readers of every process (bench/faults/fuzz_bus.py): world-events-, actions- and world-state-
DOMAIN for each world, percepts-msg, executive (-blocks, -office), memory, intention, codec.
"""

from __future__ import annotations

import json
import logging
import random
import re
import statistics
import sys
import tempfile
import time
import traceback
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager
from dataclasses import dataclass, field
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # `bus` is the package, not bench/speed/bus.py
sys.path.append(str(ROOT / "bench" / "faults"))  # after ROOT: fuzz_values, fuzz_bus, fuzz_events

from tools.alarm import raised_after  # noqa: E402

SPECIAL = ["(", ")", "((", "))", "?", "?a?b", "??", ":percepts", ":tests", ":subgoals", "NaN",
           "Infinity", "-Infinity", "nan", "inf", "1e999", "-1e999", "1e-999", str(2**63),
           str(-(2**63) - 1), "9" * 5000, "\"", "'", "`", ";", "\\", "\x00", "\u00e9", "\ud800",
           "\ufeff", "[", "]", "{", "}", ",", ":", "null", "true", "1.5e", "--1", ".", "\n"]
ALPHABET = "()?:;.-+eE0123456789 \n\t\"'`\\[]{},abcXYZ*<>="


@dataclass
class Tally:
    """What one reader did with its inputs (times [s] per input)."""

    reader: str
    inputs: int = 0
    accepted: int = 0
    refused: int = 0
    crashes: list[tuple[object, str]] = field(default_factory=list)
    hangs: list[object] = field(default_factory=list)
    unnamed: list[tuple[object, str]] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    slowest_s: float = 0.0
    slowest: object = None

    def quantile(self, q: float) -> float:
        """The q-quantile of the times [s] (0 without inputs)."""
        if not self.times:
            return 0.0
        ordered = sorted(self.times)
        return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


@dataclass(frozen=True)
class Reader:
    """How to make an input, feed it (True: accepted; False or a reason string, or a
    `refusals` error: refused), the drill's minimal cases, and what a refusal of an input
    must name (`named(reason, item)`; None: not checked)."""

    make: Callable[[random.Random], object]
    feed: Callable[[object], object]
    refusals: tuple[type[BaseException], ...]
    minimal: tuple = ()
    named: Callable[[str, object], bool] | None = None


class Hang(BaseException):
    """An input took longer than the drill's per-input limit (not an Exception: the code
    under test must not catch it)."""


def time_limit(seconds: float) -> AbstractContextManager[None]:
    """Raise Hang in this thread when the block runs longer than ``seconds``."""
    return raised_after(seconds, lambda: Hang(f"longer than {seconds:g} s"))


def located(source: str) -> Callable[[str, object], bool]:
    """A refusal of a text names ``source``:line:col (or the whole ``source``)."""
    pattern = re.compile(rf"{re.escape(source)}(:\d+:\d+)?: ")
    return lambda reason, item: bool(pattern.search(reason))


def names_field(reason: str, fields: set[str]) -> bool:
    """Whether ``reason`` names one of ``fields`` (a key or a short value of the input, as a
    word, or quoted as it is) or refuses the payload as a whole."""
    from fuzz_bus import WHOLE

    return any(w in reason for w in WHOLE) or \
        not fields.isdisjoint(re.findall(r"[\w*?-]+", reason)) or \
        any(repr(f) in reason for f in fields)   # a value shown as it is: '', 'x', 'a b'



def mutate(base: str, rng: random.Random) -> str:
    """1 to 4 random edits of `base`: cut, duplicate, insert characters or special tokens,
    deep parentheses or brackets, long digit runs."""
    text = base
    for _ in range(rng.randint(1, 4)):
        i = rng.randint(0, len(text))
        j = min(len(text), i + rng.randint(0, 40))
        op = rng.randrange(8)
        if op == 0:
            text = text[:i] + text[j:]
        elif op == 1:
            text = text[:j] + text[i:j] + text[j:]
        elif op == 2:
            text = text[:i] + "".join(rng.choice(ALPHABET) for _ in range(rng.randint(1, 8))) \
                + text[i:]
        elif op == 3:
            text = text[:i] + rng.choice(SPECIAL) + text[i:]
        elif op == 4:
            k = int(rng.paretovariate(0.6)) % 6000
            opener, closer = rng.choice(["()", "[]", "{}"])
            text = text[:i] + opener * k + text[i:] + closer * rng.randint(0, k)
        elif op == 5:
            text = text[:i] + "7" * (int(rng.paretovariate(0.5)) % 8000) + text[i:]
        elif op == 6:
            text = text[:i]
        else:
            text = text[:i] + chr(rng.randint(0, 0x2FFFF)) + text[j:]
    return text


def to_bytes(text: str, rng: random.Random) -> bytes:
    """UTF-8 bytes of `text`, sometimes with bytes that are not UTF-8 or a byte-order mark."""
    return noisy(text.encode("utf-8", errors="replace"), rng)


def noisy(data: bytes, rng: random.Random) -> bytes:
    """`data`, sometimes with random bytes inserted or a byte-order mark in front."""
    if rng.random() < 0.1:
        i = rng.randint(0, len(data))
        data = data[:i] + bytes(rng.randrange(256) for _ in range(rng.randint(1, 4))) + data[i:]
    if rng.random() < 0.02:
        data = b"\xef\xbb\xbf" + data
    return data


def corpus(*patterns: str) -> list[str]:
    return [p.read_text() for pattern in patterns for p in sorted(ROOT.glob(pattern))]


def program_reader() -> Reader:
    from agents.lang import ProgramError, load_program_text
    from agents.lang.loader import decode_text

    bases = corpus("programs/*.tlp", "tests/lang/fixtures/*.tlp", "tests/lang/programs/*.tlp",
                   "tests/lang/corpus/*/program.tlp")
    small = [b for b in bases if len(b) < 3000]

    def make(rng: random.Random) -> bytes:
        base = rng.choice(bases if rng.random() < 0.1 else small)
        return to_bytes(mutate(base, rng), rng)

    def feed(data: bytes) -> bool:
        load_program_text(decode_text(data, "fuzz.tlp"), "fuzz.tlp")
        return True

    minimal = (b"(" * 334 + b")" * 334, b"(" * 400 + b")" * 400 + b"\n",
               ("((fast ?x) :percepts ((self ?x speed ?s)) :tests ((> ?s " + "1" * 5000
                + ")))").encode(), b"((fast ?x)\n :percepts ((self ?x speed \xff\xfe))\n)\n",
               b"(operators ((delivered) :operator (serve-coffee) :effects l))\n",   # N2
               b"(operators ((delivered) :operator serve :on-failure x))\n")
    return Reader(make, feed, (ProgramError,), minimal, located("fuzz.tlp"))


def percept_reader() -> Reader:
    from agents.lang import ProgramError, parse_percepts
    from agents.lang.loader import decode_text

    bases = corpus("tests/lang/fixtures/*.txt", "tests/lang/corpus/*/percepts.txt")

    def make(rng: random.Random) -> bytes:
        return to_bytes(mutate(rng.choice(bases), rng), rng)

    def feed(data: bytes) -> bool:
        parse_percepts(decode_text(data, "fuzz.txt"), "fuzz.txt")
        return True

    minimal = (b"[" * 5000 + b"]" * 5000, b'[["self","ME","speed",' + b"9" * 5000 + b"]]",
               b"((self ME speed " + b"1" * 5000 + b"))", b'[["self","ME","speed",NaN]]',
               b'[["self","ME","speed",Infinity]]', b"(" * 334 + b")" * 334)
    return Reader(make, feed, (ProgramError,), minimal, located("fuzz.txt"))


def goal_reader() -> Reader:
    from agents.lang import GoalError, load_program
    from agents.lang.reading.goals import parse_goal

    program = load_program(ROOT / "programs" / "driving.tlp")
    bases = ["(package-delivered PACKET1)", "(at-desired-speed ?any)", "(in-right-lane ME)",
             "(not-hitting-pedestrians ME)", "(keeping-distance ?x)"]

    def make(rng: random.Random) -> str:
        return mutate(rng.choice(bases), rng)

    def feed(text: str) -> bool:
        parse_goal(text, program)
        return True

    minimal = ("(package-delivered " + "X" * 1_000_020 + ")", "(" * 5000, "(a " * 400,
               "(package-delivered " + "9" * 5000 + ")", "")
    return Reader(make, feed, (GoalError,), minimal)


def event_reader() -> Reader:
    from tools.commands.event import read_event

    bases = [json.dumps(e) for e in (
        {"kind": "pedestrian", "ahead_of": "ME", "dist": 20, "lateral": 1.5},
        {"kind": "pedestrian", "x": 10.0, "y": -3.0, "heading": 90, "speed": 1.4, "id": "W1"},
        {"kind": "block", "segment": "S17"}, {"kind": "unblock", "segment": "S17"},
        {"kind": "package", "id": "P9", "address": 3, "street": "B", "owner": "ME"})]

    def make(rng: random.Random) -> str:
        return mutate(rng.choice(bases), rng)

    def feed(text: str) -> bool:
        read_event(text)
        return True

    minimal = ("[" * 5000, '{"kind": "pedestrian", "speed": NaN}', '{"kind": "x", "n": 1e999}',
               '{"kind": "x", "n": ' + "9" * 5000 + "}", "")
    return Reader(make, feed, (click.ClickException,), minimal)


def scenario_reader(tmp: Path) -> Reader:
    """Scenario files: bytes written to a file in `tmp` (program paths there made absolute
    so that the shipped programs are found), read and checked fully as `teleo launch` does."""
    from tools.commands.scenario_check import load_checked
    from world.errors import WorldError

    bases = [text.replace('program = "programs/', f'program = "{ROOT}/programs/')
             for text in corpus("scenarios/*.toml")]
    path = tmp / "fuzz.toml"

    def make(rng: random.Random) -> bytes:
        return to_bytes(mutate(rng.choice(bases), rng), rng)

    def feed(data: bytes) -> bool:
        path.write_bytes(data)
        load_checked(path)
        return True

    minimal = (b"a = " + b"[" * 5000 + b"]" * 5000, b"[run]\nseed = " + b"9" * 5000,
               b"[run]\ndeadline = nan\n", b"[run]\ndeadline = inf\n", b"\xff\xfe[run]\n",
               b"[world]\ndomain = \"nowhere\"\n", b"[[agents]]\nid = \"ME\"\n")
    return Reader(make, feed, (WorldError,), minimal)


def request_reader(tmp: Path) -> Reader:
    from agents.processes.goals import GoalEntry, engine_validator
    from bus import keys
    from bus.codec import decode, encode
    from bus.errors import CodecError
    from bus.messages import Envelope, GoalRequest, WorldEvent
    from world.run_scenario import load_scenario

    scenario = load_scenario(ROOT / "scenarios" / "driving_demo.toml")
    log = logging.getLogger("fuzz.goals")
    log.setLevel(logging.WARNING)
    clock = iter(range(10**9))
    entry = GoalEntry(scenario, tmp / "goals.json", engine_validator(scenario), log,
                      clock=lambda: next(clock) * 0.25)  # 4 requests per second
    key = keys.goals("fuzz", "ME")
    ops = ["post", "cancel", "priority", "list", "update", "", "POST"]

    def value(rng: random.Random) -> object:
        return rng.choice([rng.randint(-2**63, 2**64 - 1), rng.randint(-5, 50), 2**64 - 1,
                           "g" + str(rng.randint(0, 40)), mutate("(package-delivered P1)", rng),
                           None, True, 1.5, float("nan"), [1, [2]], {"a": 1}, b"\x00"])

    def make(rng: random.Random) -> bytes:
        env = Envelope(1, "fuzz", -1, rng.choice(["cli", "x" * 300, "fuzz"]), 0)
        goal = f"(package-delivered P{rng.randint(1, 60)})"
        fields = [rng.choice(ops), "ME" if rng.random() < 0.9 else value(rng),
                  mutate(goal, rng) if rng.random() < 0.5 else goal,
                  rng.randint(1, 300), f"g{rng.randint(1, 40)}"]
        fields[rng.randrange(5)] = value(rng) if rng.random() < 0.3 else fields[0]
        message = WorldEvent(env, {"kind": value(rng)}) if rng.random() < 0.05 \
            else GoalRequest(env, *fields)
        try:
            data = encode(message)
        except CodecError:  # not msgpack-able (a lone surrogate, an int over 64 bits)
            data = encode(GoalRequest(env, "list", "ME"))
        if rng.random() < 0.3:
            data = noisy(mutate(data.decode("latin-1"), rng).encode("latin-1", "replace"), rng)
        return data

    def feed(data: bytes) -> bool:
        request = decode(key, data)
        if not isinstance(request, GoalRequest):
            raise CodecError(key, f"not a GoalRequest: {type(request).__name__}")
        ok, _reason, _goals, _cycle = entry.answer(request)
        return ok

    big = encode(GoalRequest(Envelope(1, "fuzz", -1, "cli", 0), "post", "ME",
                             "(package-delivered " + "X" * 1_000_000 + ")", 5))
    minimal = (big, encode(GoalRequest(Envelope(1, "fuzz", -1, "cli", 0), "post", "ME",
                                       "(package-delivered P1)", 2**64 - 1)), b"", b"\xc1")
    return Reader(make, feed, (CodecError,), minimal)


def inputs(reader: Reader, n: int, seed: int) -> Iterator[object]:
    rng = random.Random(seed)
    yield from reader.minimal[:n]
    for _ in range(n - min(n, len(reader.minimal))):
        yield reader.make(rng)


def fuzz(name: str, reader: Reader, n: int, seed: int, limit_s: float = 5.0) -> Tally:
    """Feed `n` inputs to `reader`; count accepted, refused, crashes (any other exception),
    hangs (longer than `limit_s` [s]) and refusals that name no field."""
    tally = Tally(name)
    for item in inputs(reader, n, seed):
        reason = None
        t0 = time.perf_counter()
        try:
            with time_limit(limit_s):
                got = reader.feed(item)
            if got is True:
                tally.accepted += 1
            else:
                tally.refused += 1
                reason = got if isinstance(got, str) else None
        except reader.refusals as exc:
            tally.refused += 1
            reason = str(exc)
        except Hang:
            tally.hangs.append(item)
        except Exception:  # a crash: what this drill looks for
            tally.crashes.append((item, traceback.format_exc(limit=-8)))
        elapsed = time.perf_counter() - t0
        if reason is not None and reader.named is not None and not reader.named(reason, item):
            tally.unnamed.append((item, reason))
        tally.inputs += 1
        tally.times.append(elapsed)
        if elapsed > tally.slowest_s:
            tally.slowest_s, tally.slowest = elapsed, item
    return tally


def bus_reader(make_bus) -> Callable[[], Reader]:
    """A bench/faults/fuzz_bus.py reader as a Reader (its refusals are reason strings)."""
    def made() -> Reader:
        r = make_bus()
        return Reader(r.make, r.feed, (), (), lambda reason, item: names_field(
            reason, r.fields(item)))
    return made


def make_readers(tmp: Path) -> dict[str, Callable[[], Reader]]:
    from fuzz_bus import readers

    texts = {"program": program_reader, "percepts": percept_reader, "goal": goal_reader,
             "event": event_reader, "scenario": lambda: scenario_reader(tmp),
             "request": lambda: request_reader(tmp)}
    return {**texts, **{name: bus_reader(r) for name, r in readers(tmp).items()}}


READERS = ("program", "percepts", "goal", "event", "scenario", "request",
           *(f"{what}-{d}" for d in ("driving", "blocks", "office")
             for what in ("world-events", "actions", "world-state")),
           "percepts-msg", "executive", "executive-blocks", "executive-office", "memory",
           "intention", "codec")


def describe(item: object) -> str:
    from bus.schema import brief

    return brief(item, 100)


@click.command()
@click.option("--n", default=100_000, type=click.IntRange(min=1), show_default=True,
              help="Inputs per reader.")
@click.option("--seed", default=1, show_default=True)
@click.option("--reader", "names", multiple=True, type=click.Choice(READERS),
              help="Only these readers (repeatable; default: all).")
@click.option("--out", type=click.Path(file_okay=False), help="Write crashing inputs here.")
@click.option("--limit", "limit_s", default=5.0, show_default=True,
              help="Seconds an input may take before it counts as a hang.")
def main(n: int, seed: int, names: tuple[str, ...], out: str | None, limit_s: float) -> None:
    """Fuzz every reader with N inputs and print what happened."""
    crashes = 0
    with tempfile.TemporaryDirectory() as tmp:
        readers = make_readers(Path(tmp))
        click.echo(f"{'reader':<20} {'inputs':>7} {'accepted':>8} {'refused':>8} {'crashes':>7} "
                   f"{'hangs':>5} {'unnamed':>7} {'median ms':>9} {'p99 ms':>7} {'max ms':>7}")
        for name in names or READERS:
            tally = fuzz(name, readers[name](), n, seed, limit_s)
            crashes += len(tally.crashes) + len(tally.hangs) + len(tally.unnamed)
            click.echo(f"{name:<20} {tally.inputs:>7} {tally.accepted:>8} {tally.refused:>8} "
                       f"{len(tally.crashes):>7} {len(tally.hangs):>5} {len(tally.unnamed):>7} "
                       f"{statistics.median(tally.times) * 1e3:>9.3f} "
                       f"{tally.quantile(0.99) * 1e3:>7.2f} {tally.slowest_s * 1e3:>7.1f}")
            for k, (item, trace) in enumerate(tally.crashes[:3]):
                click.echo(f"  crash {k + 1}: {describe(item)}\n{trace}")
            for k, item in enumerate(tally.hangs[:3]):
                click.echo(f"  hang {k + 1}: {describe(item)}")
            for k, (item, reason) in enumerate(tally.unnamed[:3]):
                click.echo(f"  unnamed {k + 1}: {describe(item)}: {reason[:200]}")
            if out:
                for k, (item, _trace) in enumerate(tally.crashes):
                    path = Path(out) / f"{name}-{k}.bin"
                    path.parent.mkdir(parents=True, exist_ok=True)
                    path.write_bytes(item if isinstance(item, bytes)
                                     else str(item).encode("utf-8", "surrogatepass"))
    sys.exit(1 if crashes else 0)


if __name__ == "__main__":
    main()
