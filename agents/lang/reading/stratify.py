"""Stratified negation: concept SCCs in bottom-up order; negation inside an SCC is rejected."""

from __future__ import annotations

from collections.abc import Iterable

from ..core.program import ConceptClause


def dependency_graph(clauses: Iterable[ConceptClause]) -> dict[str, dict[str, list]]:
    """pred -> {depends-on pred -> [negated Literal or None, ...]}."""
    graph: dict[str, dict[str, list]] = {}
    for c in clauses:
        edges = graph.setdefault(c.head.pred, {})
        for lit in c.relations:
            edges.setdefault(lit.pred, []).append(lit if lit.negated else None)
    return graph


def sccs(graph: dict[str, dict[str, list]]) -> list[list[str]]:
    """Strongly connected components, dependencies first (iterative Tarjan, deterministic)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on: set[str] = set()
    stack: list[str] = []
    out: list[list[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph.get(root, {}))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            node, it = work[-1]
            nxt = next(it, None)
            if nxt is not None:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on.add(nxt)
                    work.append((nxt, iter(sorted(graph.get(nxt, {})))))
                elif nxt in on:
                    low[node] = min(low[node], index[nxt])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    x = stack.pop()
                    on.discard(x)
                    comp.append(x)
                    if x == node:
                        break
                out.append(sorted(comp))
    return out


def negative_cycle(graph: dict[str, dict[str, list]], comp: list[str]):
    """(negated literal, cycle of preds) for a negation inside ``comp``, or None."""
    members = set(comp)
    for p in comp:
        for q, lits in sorted(graph.get(p, {}).items()):
            neg = next((lit for lit in lits if lit is not None), None)
            if q in members and neg is not None:
                return neg, [p, *_path(graph, q, p, members)]
    return None


def _path(graph: dict[str, dict[str, list]], src: str, dst: str, members: set[str]) -> list[str]:
    """Shortest path src .. dst inside ``members`` (BFS), as a list of preds ending at dst."""
    prev: dict[str, str | None] = {src: None}
    queue = [src]
    while queue:
        x = queue.pop(0)
        if x == dst:
            break
        for y in sorted(graph.get(x, {})):
            if y in members and y not in prev:
                prev[y] = x
                queue.append(y)
    path, x = [], dst
    while x is not None:
        path.append(x)
        x = prev.get(x)
    return path[::-1]
