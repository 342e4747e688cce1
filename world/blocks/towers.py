"""Random towers: `[world] random_towers = N` or `{ blocks = N, towers = K, seed = S }` draws N
blocks named A, B, C, ... into at most K towers (default: every column but one, so a block can
always be put down), from `seed` (default: the run's seed). One seed, one layout.

    >>> random_towers({"blocks": 5, "seed": 3}, 0, 6) == random_towers(5, 3, 6)
    True
    >>> sorted(n for t in random_towers(5, 3, 6) for n in t)
    ['A', 'B', 'C', 'D', 'E']
"""

from __future__ import annotations

import random
import string
from typing import Any

from world.errors import ConfigError

MAX_BLOCKS = 25     # letters, less the table's name


def random_towers(value: Any, seed: int, columns: int,
                  avoid: str = "T") -> tuple[tuple[str, ...], ...]:
    """Towers (bottom first, tower k in column k) drawn from `seed`, no block named `avoid`
    (the table); raises ConfigError."""
    if isinstance(value, dict):
        unknown = sorted(set(value) - {"blocks", "towers", "seed"})
        if unknown:
            raise ConfigError(f"[world] random_towers: unknown keys {unknown}; known: "
                              f"['blocks', 'seed', 'towers']")
        count, most = value.get("blocks"), value.get("towers", max(1, columns - 1))
        seed = value.get("seed", seed)
    else:
        count, most = value, max(1, columns - 1)
    for key, v, hi in (("blocks", count, MAX_BLOCKS), ("towers", most, columns)):
        if isinstance(v, bool) or not isinstance(v, int) or not 1 <= v <= hi:
            raise ConfigError(f"[world] random_towers.{key}: expected an integer in [1, {hi}], "
                              f"got {v!r}")
    if isinstance(seed, bool) or not isinstance(seed, int):
        raise ConfigError(f"[world] random_towers.seed: expected an integer, got {seed!r}")
    rng = random.Random(seed)
    names = [c for c in string.ascii_uppercase if c != avoid][:count]
    rng.shuffle(names)
    k = rng.randint(1, min(most, count))
    cuts = sorted(rng.sample(range(1, count), k - 1)) if k > 1 else []
    bounds = [0, *cuts, count]
    return tuple(tuple(names[a:b]) for a, b in zip(bounds, bounds[1:], strict=False))
