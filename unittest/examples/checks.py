"""What the example checks (check_*.py) share: printing a list of named checks
and the verdict that ctest matches (PASS_REGULAR_EXPRESSION "PASSED")."""


def verdict(checks):
    """checks: [(name, bool)]; prints one line each, then PASSED or FAILED; returns the exit code"""
    ok = True
    for name, good in checks:
        print(("ok    " if good else "FAIL  ") + name)
        ok &= bool(good)
    print("PASSED" if ok else "FAILED")
    return 0 if ok else 1
