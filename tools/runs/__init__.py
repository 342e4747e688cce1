"""A running launch as every tool reaches it: the run registry (runfile), which bus a command
talks to (target), the rates of its keys (rates). Imports no other room of tools/.
"""
