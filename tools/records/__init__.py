"""What a run leaves behind and how it is read: the run record (run_record reads it, recorder
writes it, record_coverage says what it lacks, replayer and player play it back), the
decision as a tree, and the end-of-run summaries of launch and simulate. Imports tools/runs only.
"""
