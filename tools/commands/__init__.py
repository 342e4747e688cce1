"""The `teleo` commands, one module per area (tools/cli.py loads each only when its command is
asked for), and the helpers only commands use. Imports tools/launching, tools/records and
tools/runs; outside this room only tools/cli.py names a command module (by its name).
"""
