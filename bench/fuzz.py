"""Fuzz drill of teleo's readers (issue 11; fault drill 4): any input gives teleo's own error.

    .venv/bin/python bench/fuzz.py [--n 100000] [--seed 1] [--reader NAME ...] [--out DIR]

For each reader it feeds N inputs: the drill's minimal cases first, then mutations of real
inputs (the repository's programs and percept files, goals, world events, encoded goal
requests) and generated extremes (deep nesting, long numbers and tokens, NaN, bytes that are
not UTF-8). An input is *accepted* or *refused* with the reader's own error (ProgramError,
GoalError, a click error, CodecError, or a goal reply with ok false); anything else is a
*crash*. Printed per reader: inputs, crashes (0 expected), accepted, refused, and the slowest
input's time. With --out, each crashing input is written there to replay.

The readers: program (bytes -> decode_text -> load_program_text), percepts (bytes ->
decode_text -> parse_percepts), goal (parse_goal against programs/driving.tlp), event (the
JSON argument of `teleo event`), scenario (bytes -> a scenario file, read and checked fully
as `teleo launch` does), request (bytes -> bus.codec.decode -> the goal-entry
process's answer, with the scenarios/driving_demo.toml agents and a real store file).
"""

from __future__ import annotations

import json
import logging
import random
import sys
import tempfile
import time
import traceback
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # `bus` is the package, not bench/bus.py

SPECIAL = ["(", ")", "((", "))", "?", "?a?b", "??", ":percepts", ":tests", ":subgoals", "NaN",
           "Infinity", "-Infinity", "nan", "inf", "1e999", "-1e999", "1e-999", str(2**63),
           str(-(2**63) - 1), "9" * 5000, "\"", "'", "`", ";", "\\", "\x00", "\u00e9", "\ud800",
           "\ufeff", "[", "]", "{", "}", ",", ":", "null", "true", "1.5e", "--1", ".", "\n"]
ALPHABET = "()?:;.-+eE0123456789 \n\t\"'`\\[]{},abcXYZ*<>="


@dataclass
class Tally:
    """What one reader did with its inputs."""

    reader: str
    inputs: int = 0
    accepted: int = 0
    refused: int = 0
    crashes: list[tuple[object, str]] = field(default_factory=list)
    slowest_s: float = 0.0
    slowest: object = None


@dataclass(frozen=True)
class Reader:
    """How to make an input, feed it (True: accepted; a `refusals` error: refused), and the
    drill's minimal cases."""

    make: Callable[[random.Random], object]
    feed: Callable[[object], bool]
    refusals: tuple[type[BaseException], ...]
    minimal: tuple = ()


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
                + ")))").encode(), b"((fast ?x)\n :percepts ((self ?x speed \xff\xfe))\n)\n")
    return Reader(make, feed, (ProgramError,), minimal)


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
    return Reader(make, feed, (ProgramError,), minimal)


def goal_reader() -> Reader:
    from agents.lang import GoalError, load_program
    from agents.lang.goals import parse_goal

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
    from tools.event_commands import read_event

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
    from tools.scenario_check import load_checked
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


def fuzz(name: str, reader: Reader, n: int, seed: int) -> Tally:
    """Feed `n` inputs to `reader`; count accepted, refused and crashes (any other exception)."""
    tally = Tally(name)
    for item in inputs(reader, n, seed):
        t0 = time.perf_counter()
        try:
            if reader.feed(item):
                tally.accepted += 1
            else:
                tally.refused += 1
        except reader.refusals:
            tally.refused += 1
        except Exception:  # a crash: what this drill looks for
            tally.crashes.append((item, traceback.format_exc(limit=-3)))
        elapsed = time.perf_counter() - t0
        tally.inputs += 1
        if elapsed > tally.slowest_s:
            tally.slowest_s, tally.slowest = elapsed, item
    return tally


def make_readers(tmp: Path) -> dict[str, Callable[[], Reader]]:
    return {"program": program_reader, "percepts": percept_reader, "goal": goal_reader,
            "event": event_reader, "scenario": lambda: scenario_reader(tmp),
            "request": lambda: request_reader(tmp)}


def describe(item: object) -> str:
    text = repr(item)
    return text if len(text) <= 60 else f"{text[:60]}... ({len(item)} long)"


@click.command()
@click.option("--n", default=100_000, type=click.IntRange(min=1), show_default=True,
              help="Inputs per reader.")
@click.option("--seed", default=1, show_default=True)
@click.option("--reader", "names", multiple=True,
              type=click.Choice(["program", "percepts", "goal", "event", "scenario",
                                 "request"]),
              help="Only these readers (repeatable; default: all).")
@click.option("--out", type=click.Path(file_okay=False), help="Write crashing inputs here.")
def main(n: int, seed: int, names: tuple[str, ...], out: str | None) -> None:
    """Fuzz every reader with N inputs and print what happened."""
    crashes = 0
    with tempfile.TemporaryDirectory() as tmp:
        readers = make_readers(Path(tmp))
        for name in names or tuple(readers):
            t0 = time.perf_counter()
            tally = fuzz(name, readers[name](), n, seed)
            crashes += len(tally.crashes)
            click.echo(f"{name:<9} inputs {tally.inputs}, crashes {len(tally.crashes)}, accepted "
                       f"{tally.accepted}, refused {tally.refused}; slowest input "
                       f"{tally.slowest_s * 1e3:.1f} ms ({describe(tally.slowest)}); "
                       f"total {time.perf_counter() - t0:.1f} s")
            for k, (item, trace) in enumerate(tally.crashes[:3]):
                click.echo(f"  crash {k + 1}: {describe(item)}\n{trace}")
            if out:
                for k, (item, _trace) in enumerate(tally.crashes):
                    path = Path(out) / f"{name}-{k}.bin"
                    path.parent.mkdir(parents=True, exist_ok=True)
                    path.write_bytes(item if isinstance(item, bytes)
                                     else str(item).encode("utf-8", "surrogatepass"))
    sys.exit(1 if crashes else 0)


if __name__ == "__main__":
    main()
