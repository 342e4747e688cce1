"""The worlds agents act in, and the world process that is the clock of a run.

domain        the contract every domain meets (World, Domain) and the registry of domains
driving/      the urban driving city of seed 000 (Tables 3 and 4)
run_scenario  scenario files ([run], [world], [[agents]], [[goals]], [[events]])
process       the world process on the bus (the only module here that touches the bus)
recorder      the run folder's files: trace, health, snapshots, checkpoints, final totals
resume        a restarted world back at the cycle the run had reached (checkpoint + replay)
angles        angle arithmetic shared by domains
"""
