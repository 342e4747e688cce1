"""The shared nouns every room uses: terms, errors, limits, s-expressions, arithmetic,
percept columns and fact stores, the matcher, goals' conjunctions, the Program,
outcomes, the Decision and its explanation, and the Mechanism protocol."""
