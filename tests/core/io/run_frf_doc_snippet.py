"""Runs the Python snippet of docs/frf_format.md and checks it against gearpath both ways.

1. exec the one ```python block of the document in a scratch directory (it writes and reads
   back "example_set");
2. run test_io's FrfSetFromPython test, which loads that set with gearpath::ReadFrfSet;
3. run test_io's FrfSetForPython test, which writes a set with gearpath::WriteFrfSet, and read
   it with the snippet's read_frf_set.
Usage: run_frf_doc_snippet.py <frf_format.md> <scratch dir> <test_io executable>
"""
import math
import os
import re
import shutil
import subprocess
import sys


def run_gtest(test_io, gtest_filter, env_name, env_value):
    env = dict(os.environ, **{env_name: env_value})
    result = subprocess.run([test_io, "--gtest_filter=" + gtest_filter], env=env,
                            capture_output=True, text=True, check=False)
    print(result.stdout)
    if result.returncode != 0 or "[  PASSED  ] 1 test." not in result.stdout:
        sys.exit(f"{gtest_filter} failed or did not run")


def main():
    doc, scratch, test_io = sys.argv[1:4]
    with open(doc) as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    if len(blocks) != 1:
        sys.exit(f"{doc}: expected exactly one python code block, found {len(blocks)}")
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    os.chdir(scratch)
    namespace = {"__name__": "__main__"}
    exec(compile(blocks[0], doc, "exec"), namespace)

    run_gtest(test_io, "FrfSetFromPython.*", "GEARPATH_PYTHON_FRF_SET",
              os.path.join(scratch, "example_set"))

    cxx_set = os.path.join(scratch, "cxx_set")
    run_gtest(test_io, "FrfSetForPython.*", "GEARPATH_FRF_SET_FOR_PYTHON", cxx_set)
    manifest, f, H, coupled = namespace["read_frf_set"](cxx_set)
    assert H.shape == (4, 2, 3) and H.dtype == "complex128", H.shape
    assert sorted(coupled) == ["aa", "ap", "ma", "mp", "pa", "pp"], sorted(coupled)
    assert coupled["pa"].shape == (4, 3, 2)
    x = 2.0 + f[2] + 0.1
    expected = complex(math.sin(x) / 3.0, -math.cos(x) * 1e-7)
    assert abs(coupled["pa"][2, 1, 0] - expected) <= 1e-15, (coupled["pa"][2, 1, 0], expected)
    assert manifest["coupled"]["dofs"]["m"][0]["name"] == "m1x"
    print("python <-> gearpath FRF set exchange OK")


if __name__ == "__main__":
    main()
