"""Runs the examples of README.md, so that they stay true.

Usage: TestReadmeExamples.py REPO_ROOT PYTHONPATH_FOR_TETMESHER [PVPYTHON PVPYTHON_PATH]
A block preceded by `<!-- example: python -->` runs with /usr/bin/python3, by
`<!-- example: pvpython -->` with pvpython, and `<!-- example: cpp FILE -->` must equal FILE
(which another test compiles and runs).
"""
import os
import re
import subprocess
import sys

root, python_path = sys.argv[1], sys.argv[2]
pvpython = sys.argv[3] if len(sys.argv) > 3 else ""
pvpython_path = sys.argv[4] if len(sys.argv) > 4 else ""
readme = open(os.path.join(root, "README.md")).read()
blocks = re.findall(r"<!-- example: (\w+)\s*([^>]*?)\s*-->\s*```\w*\n(.*?)```", readme, re.S)
failures = []
seen = set()
for kind, argument, code in blocks:
    seen.add(kind)
    if kind == "cpp":
        with open(os.path.join(root, argument)) as f:
            if f.read().strip() != code.strip():
                failures.append(f"README's C++ example differs from {argument}")
        continue
    if kind == "python":
        command = ["/usr/bin/python3", "-c", code]
        env = dict(os.environ, PYTHONPATH=python_path)
    elif kind == "pvpython":
        if not pvpython:
            failures.append("no pvpython given for the pvpython example")
            continue
        command = [pvpython, "--force-offscreen-rendering", "-c", code]
        env = dict(os.environ, PYTHONPATH=pvpython_path)
    else:
        failures.append(f"unknown example kind {kind}")
        continue
    result = subprocess.run(command, cwd=root, env=env, capture_output=True, text=True, timeout=600)
    print(f"--- {kind} example: exit {result.returncode}\n{result.stdout}{result.stderr}")
    if result.returncode != 0:
        failures.append(f"the {kind} example failed")
for wanted in ("python", "pvpython", "cpp"):
    if wanted not in seen:
        failures.append(f"README has no {wanted} example")
if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"TestReadmeExamples: {len(blocks)} examples ok")
