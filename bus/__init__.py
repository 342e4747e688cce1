"""teleo's bus layer: everything that crosses a process boundary, on Eclipse Zenoh with
msgpack payloads, and the cycle clock. See docs/bus.md.

keys (key layout), messages + codec (what travels), config (how to join), node (one
session: publish, subscribe, query, liveliness), router (the hub), cycle (pure
bookkeeping), stage (agent side of the cycle), clock (world side of the cycle).
"""
