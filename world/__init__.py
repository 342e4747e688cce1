"""The urban driving world of seed 000 ("An Illustrative Domain", Tables 3 and 4).

scenario    WorldConfig and load_world_config (the `[world]` table of a scenario)
city        static geometry: streets, segments, intersections, lane lines, buildings
simulation  Simulation: pymunk bodies, the agent cars' actions, traffic, pedestrians, events
snapshot    WorldSnapshot: the frozen state of a cycle, plain-data round trip
perception  perceive(snapshot, agent): the agent's percepts (documented in percepts.md)
navigation  route guidance for carried packages
render      render_png / render_gif for people
process     the world process on the bus (the only module here that touches the bus)
"""
