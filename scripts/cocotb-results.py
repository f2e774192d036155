"""Reads a cocotb results file (JUnit XML) and fails unless exactly the
expected number of tests ran and all passed: cocotb's make exits 0 when a
test fails, so the examples' run.sh scripts check its results this way.

    python3 scripts/cocotb-results.py RESULTS.xml EXPECTED
"""
import sys
import xml.etree.ElementTree as ET

results, expected = sys.argv[1], int(sys.argv[2])
failed, passed = [], 0
for case in ET.parse(results).getroot().iter("testcase"):
    if case.find("failure") is not None or case.find("error") is not None:
        failed.append(case.get("name"))
    else:
        passed += 1
if failed or passed != expected:
    sys.exit(f"error: {passed} of {expected} cocotb tests passed; failed: {failed}")
print(f"  all {passed} cocotb tests passed")
