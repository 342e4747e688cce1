"""How a skill path is chosen and run: the executive's goal walk, the path finder
and body runners, effects, loop and circle watches, and the EngineState."""
