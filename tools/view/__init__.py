"""placeholder"""
commands = []
