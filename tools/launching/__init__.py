"""What one `teleo launch` starts (run_plan), how it supervises and restarts its processes
(supervisor, supervision) and stops its run (run_stop, stop_signals), with its secrets,
cores, disk space and progress bar. Imports tools/records and tools/runs, never tools/commands.
"""
