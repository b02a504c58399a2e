#!/usr/bin/env python3
"""Checks that every test CTest lists carries an environment setting (the per-pass GL state check's
LIGHTPASS_GL_STATE_CHECKS=1), so a bare `ctest` in the build folder runs the check as scripts/test does.

    ctest_environment.py CTEST BUILD_DIR NAME=VALUE
"""
import json
import subprocess
import sys


def tests_without(listing, setting):
    """Names of the tests in `ctest --show-only=json-v1` output whose ENVIRONMENT lacks setting."""
    missing = []
    for test in listing.get("tests", []):
        env = []
        for prop in test.get("properties", []):
            if prop.get("name") == "ENVIRONMENT":
                env += prop.get("value", [])
        if setting not in env:
            missing.append(test["name"])
    return missing


def main(ctest, build_dir, setting):
    out = subprocess.run([ctest, "--show-only=json-v1"], cwd=build_dir, check=True,
                         capture_output=True, text=True).stdout
    listing = json.loads(out)
    count = len(listing.get("tests", []))
    missing = tests_without(listing, setting)
    if count == 0:
        print(f"{build_dir}: ctest lists no test")
        return 1
    if missing:
        print(f"{len(missing)} of {count} tests run without {setting}: " + ", ".join(missing[:20]))
        return 1
    print(f"all {count} tests run with {setting}")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
