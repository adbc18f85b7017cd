# Shared by the model tests that check a lowered program in Python
# (check_program in cli_lib.sh runs their scripts with this folder on the
# module path): one list of failed expectations, and the program's one arm.
problems = []


def want(ok, what):
    """Records `what` as a failed expectation unless `ok`."""
    if not ok:
        problems.append(what)


def single_arm(ir):
    """The program's arm solver, expecting exactly one."""
    arms = ir["arms"]
    want(len(arms) == 1, f"one arm solver, got {len(arms)}")
    return arms[0]


def report():
    """Prints one line per failed expectation (none: the program is the intended one)."""
    for line in problems:
        print(line)
