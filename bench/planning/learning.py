"""Benchmark: the learning curve of means-ends problem solving in the Blocks World (seed 000,
"Problem Solving and Skill Learning": learned skills "let the agent achieve goals that require
many steps purely through skill execution, rather than by resorting to deliberative problem
solving").

N random problems (towers of 3 to 8 blocks, goals (clear X), (on X Y), (ontable X T), each
false at the start) are solved by programs/blocks.tlp, which holds primitive skills only:
  fresh    each problem from no learned skills (the baseline: search every time);
  pass 1   the problems in turn from an empty learned file, each starting from what the ones
           before it taught (the learning curve);
  pass 2   the same problems again, from the learned file pass 1 wrote.
Per pass: problems solved, cycles, problem-solving cycles (cycles in which the solver ran, on
an impasse), wall time; then the ratio of problem-solving cycles, fresh / pass 2 and
pass 1 / pass 2. The world is the Blocks World simulation (world/blocks, pymunk) when it is
installed (--world sim), else a small deterministic model with the same percepts
(--world model); the first line says which.
Run: .venv/bin/python bench/planning/learning.py [--problems 30] [--seed 1] [--world sim|model]
"""

from __future__ import annotations

import argparse
import random
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from agents.lang import Engine, GoalStatus, load_program  # noqa: E402
from agents.lang.loader import read_text  # noqa: E402
from agents.lang.registry import learned_text, read_learned  # noqa: E402

MAX_CYCLES = 120   # per problem [cycles]


@dataclass(frozen=True)
class Problem:
    towers: tuple[tuple[str, ...], ...]   # bottom first
    goal: str


@dataclass
class Tally:
    solved: int = 0
    cycles: int = 0
    solving: int = 0
    wall: float = 0.0


class ModelWorld:
    """Blocks on a table T in columns 3 m apart, 2 m blocks, one hand: the percepts of
    programs/blocks.tlp's header, and the four actions applied exactly."""

    def __init__(self, towers: tuple[tuple[str, ...], ...]):
        self.columns = [list(t) for t in towers]
        self.holding: str | None = None

    def percepts(self) -> list[list]:
        out = [["table", "T", "xpos", 0, "ypos", 0, "height", 2],
               ["hand", "H1", "status", self.holding or "empty"]]
        for k, column in enumerate(self.columns):
            out += [["block", b, "xpos", 3 * k, "ypos", 2 + 2 * level, "height", 2]
                    for level, b in enumerate(column)]
        if self.holding:
            out.append(["block", self.holding, "xpos", 99, "ypos", 99, "height", 2])
        return out

    def apply(self, actions: list[list]) -> None:
        for name, block, where in actions:
            if name in ("*unstack", "*pickup"):
                column = next(c for c in self.columns if c and c[-1] == block)
                column.pop()
                self.holding = block
            elif name == "*putdown":
                free = next((c for c in self.columns if not c), None)
                if free is None:
                    self.columns.append(free := [])
                free.append(block)
                self.holding = None
            else:
                next(c for c in self.columns if c and c[-1] == where).append(block)
                self.holding = None


class SimWorld:
    """The Blocks World simulation (world/blocks) behind the World protocol."""

    def __init__(self, towers: tuple[tuple[str, ...], ...]):
        from world.domain import get_domain

        self.domain = get_domain("blocks")
        self.world = self.domain.create({"towers": [list(t) for t in towers]}, 0, ["ME"])

    def percepts(self) -> list[list]:
        return self.domain.perceive(self.world.snapshot_dict(), "ME")

    def apply(self, actions: list[list]) -> None:
        self.world.apply_actions("ME", actions)
        self.world.step()


def problems(n: int, seed: int) -> list[Problem]:
    """``n`` random problems whose goal is false at the start."""
    rnd = random.Random(seed)
    out: list[Problem] = []
    while len(out) < n:
        names = [chr(ord("A") + k) for k in range(rnd.randint(3, 8))]
        rnd.shuffle(names)
        towers: list[list[str]] = [[] for _ in range(rnd.randint(1, 3))]
        for b in names:
            rnd.choice(towers).append(b)
        towers = [t for t in towers if t]
        x, y = rnd.sample(names, 2)
        below = {t[i + 1]: t[i] for t in towers for i in range(len(t) - 1)}
        kind = rnd.choice(["clear", "on", "ontable"])
        if kind == "clear" and any(t[-1] == x for t in towers) or \
                kind == "on" and below.get(x) == y or kind == "ontable" and x not in below:
            continue   # already true
        goal = {"clear": f"(clear {x})", "on": f"(on {x} {y})", "ontable": f"(ontable {x} T)"}
        out.append(Problem(tuple(map(tuple, towers)), goal[kind]))
    return out


def solve(engine: Engine, world_kind: type, problem: Problem, learned: tuple[str, ...]
          ) -> tuple[bool, int, int, tuple[str, ...]]:
    """(solved, cycles, problem-solving cycles, learned skills after) for one problem."""
    state = engine.initial_state(learned=learned)
    state = engine.add_goal(state, problem.goal, goal_id="g1")
    world = world_kind(problem.towers)
    solving = 0
    for cycle in range(MAX_CYCLES):
        result = engine.cycle(state, world.percepts())
        state = result.state
        section = result.decision.section("solver")
        solving += bool(section and section.solving)
        status = result.decision.status_of("g1")
        if status in (GoalStatus.SATISFIED, GoalStatus.FAILED):
            return status is GoalStatus.SATISFIED, cycle, solving, state.learned
        world.apply([a.to_list() for a in result.decision.actions])
    return False, MAX_CYCLES, solving, state.learned


def run_pass(engine: Engine, world_kind: type, todo: list[Problem], learned: tuple[str, ...],
             carry: bool, groups: int = 3) -> tuple[Tally, tuple[str, ...], list[Tally]]:
    """Solve ``todo`` in order; ``carry``: each problem starts from what the earlier ones
    learned. Returns the tally, the skills learned, and tallies per consecutive group."""
    total, parts = Tally(), [Tally() for _ in range(groups)]
    for i, problem in enumerate(todo):
        start = time.perf_counter()
        ok, cycles, solving, after = solve(engine, world_kind, problem, learned)
        wall = time.perf_counter() - start
        if carry:
            learned = after
        for t in (total, parts[i * groups // len(todo)]):
            t.solved += ok
            t.cycles += cycles
            t.solving += solving
            t.wall += wall
    return total, learned, parts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--problems", type=int, default=30)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--world", choices=["sim", "model"], default=None)
    args = parser.parse_args()
    from world.domain import DOMAINS

    kind = args.world or ("sim" if "blocks" in DOMAINS else "model")
    world_kind = SimWorld if kind == "sim" else ModelWorld
    program = load_program(ROOT / "programs" / "blocks.tlp")
    engine = Engine(program)
    todo = problems(args.problems, args.seed)
    print(f"learning bench: {len(todo)} random Blocks World problems (3-8 blocks, seed "
          f"{args.seed}), world: {'world/blocks simulation' if kind == 'sim' else 'model'}")
    fresh, _, _ = run_pass(engine, world_kind, todo, (), carry=False)
    first, learned, curve = run_pass(engine, world_kind, todo, (), carry=True)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "learned.tlp"
        path.write_text(learned_text(learned, "programs/blocks.tlp"))
        learned = read_learned(program, read_text(path), str(path))
    second, _, _ = run_pass(engine, world_kind, todo, learned, carry=True)
    print(f"{'pass':<8} {'solved':>8} {'cycles':>7} {'solving':>8} {'wall [s]':>9}")
    for name, t in (("fresh", fresh), ("pass 1", first), ("pass 2", second)):
        print(f"{name:<8} {t.solved:>5}/{len(todo):<2} {t.cycles:>7} {t.solving:>8} "
              f"{t.wall:>9.2f}")
    print("pass 1 by thirds (problem-solving cycles): "
          + " ".join(str(t.solving) for t in curve))
    print(f"learned skills: {len(learned)}")
    print(f"problem-solving cycles: fresh / pass 2 = {_ratio(fresh.solving, second.solving)}, "
          f"pass 1 / pass 2 = {_ratio(first.solving, second.solving)}; cycles: fresh / pass 2 "
          f"= {_ratio(fresh.cycles, second.cycles)}; wall: fresh / pass 2 = "
          f"{_ratio(fresh.wall, second.wall)}")


def _ratio(a: float, b: float) -> str:
    """a / b, or, with nothing left in b, the cut as a percentage."""
    if b:
        return f"{a / b:.1f}x"
    return f"{a:g} -> 0 (cut by 100%)" if a else "0 -> 0"


if __name__ == "__main__":
    main()
