"""Blocks World (seed 000, Figure 3) checked cycle by cycle against constructed states."""

from __future__ import annotations

from agents.lang import GoalStatus


def percepts(support: dict[str, str], holding: str | None = None) -> list[list]:
    """Percepts for blocks resting on "T" (the table) or on another block; one column per
    tower, a held block off the table at ypos 99."""
    out = [["table", "T", "xpos", 0, "ypos", 0, "height", 2],
           ["hand", "H1", "status", holding or "empty"]]
    columns: dict[str, int] = {}

    def place(b: str) -> tuple[int, int]:
        under = support[b]
        if under == "T":
            return columns.setdefault(b, 3 * len(columns)), 2
        x, y = place(under)
        return x, y + 2

    for b in sorted(support):
        x, y = (99, 99) if b == holding else place(b)
        out.append(["block", b, "xpos", x, "ypos", y, "height", 2])
    return out


def act(support: dict, holding: str | None, action: list):
    """Apply one action the way the world would; fail loudly on an illegal one."""
    name, *args = action
    if name in ("*unstack", "*pickup"):
        block, source = args
        assert holding is None and support[block] == source
        return {**support, block: "hand"}, block
    block, target = args
    assert holding == block
    return {**support, block: target}, None


def run(engine, state, support, holding=None, cycles=10):
    trace = []
    for _ in range(cycles):
        result = engine.cycle(state, percepts(support, holding))
        state = result.state
        trace.append((result.decision, [a.to_list() for a in result.decision.actions]))
        for a in result.decision.actions:
            support, holding = act(support, holding, a.to_list())
    return trace, support, holding


def test_beliefs_of_a_tower(blocks):
    beliefs = {str(b) for b in blocks.infer(percepts({"A": "T", "B": "A", "C": "B"}))}
    assert {"(on B A)", "(on C B)", "(ontable A T)", "(clear C)", "(hand-empty)",
            "(unstackable C B)", "(above C A)", "(above C B)", "(above B A)"} <= beliefs
    assert not {"(clear A)", "(clear B)", "(on A B)", "(above A C)"} & beliefs


def test_figure3_clear_a(blocks):
    """Goal (clear A) with C on B on A: unstack C, put it down, unstack B (seed 000, Fig. 3)."""
    trace, support, holding = run(blocks, blocks.initial_state(), {"A": "T", "B": "A", "C": "B"},
                                  cycles=4)
    assert [actions for _, actions in trace] == [
        [["*unstack", "C", "B"]], [["*putdown", "C", "T"]], [["*unstack", "B", "A"]], []]
    first = trace[0][0]
    assert [(s.goal, s.skill) for s in first.path] == [
        ("(clear A)", "clear#2"), ("(unstackable B A)", "unstackable#1"),
        ("(clear B)", "clear#1")]
    assert [s.mode for s in trace[1][0].path] == ["continued", "continued", "entered"]
    assert trace[3][0].goals[0].status is GoalStatus.SATISFIED
    assert support == {"A": "T", "B": "hand", "C": "T"} and holding == "B"


def test_stack_a_on_c_from_a_tower(blocks):
    state = blocks.add_goal(blocks.initial_state(), "(on A C)", priority=0)
    trace, support, holding = run(blocks, state, {"A": "T", "B": "A", "C": "T"}, cycles=6)
    assert [actions for _, actions in trace] == [
        [["*unstack", "B", "A"]], [["*putdown", "B", "T"]], [["*pickup", "A", "T"]],
        [["*stack", "A", "C"]], [], []]
    assert support["A"] == "C" and holding is None
    # goal p1 (clear A) was satisfied throughout the (on A C) work but is rechecked each cycle
    assert trace[-1][0].goals[0].status is GoalStatus.SATISFIED


def test_goal_with_variable_clears_every_block(blocks):
    state = blocks.remove_goal(blocks.initial_state(), "p1")
    state = blocks.add_goal(state, "(ontable ?b T)")
    trace, support, _ = run(blocks, state, {"A": "T", "B": "A", "C": "B"}, cycles=6)
    assert support == {"A": "T", "B": "T", "C": "T"}
    assert trace[-1][0].goals[0].status is GoalStatus.SATISFIED
    assert trace[0][0].goals[0].instance == "(ontable B T)"
