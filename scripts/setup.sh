#!/usr/bin/env bash
# Installs the FPGA tools tritri drives, and CGAL (the software baseline,
# compiled by tritri-cosim's `cgal` module), from Debian's packages when
# they are missing.
set -euo pipefail
need=()
for tool in iverilog verilator yosys; do
  command -v "$tool" >/dev/null 2>&1 || need+=("$tool")
done
[ -f /usr/include/CGAL/box_intersection_d.h ] || need+=(libcgal-dev)
if [ ${#need[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq iverilog verilator yosys libcgal-dev >/dev/null
fi
echo "iverilog: $(iverilog -V 2>&1 | head -1)"
echo "verilator: $(verilator --version)"
echo "yosys: $(yosys -V)"
echo "cgal: $(dpkg-query -W -f '${Version}' libcgal-dev)"

# Python tools of the examples (cocotb, FuseSoC), pinned in
# scripts/python-requirements.txt, in a project-local virtual environment.
cd "$(dirname "$0")/.."
if [ ! -x build/venv/bin/python ]; then
  python3 -m venv build/venv
fi
build/venv/bin/pip install --quiet --disable-pip-version-check -r scripts/python-requirements.txt
echo "python tools: $(build/venv/bin/cocotb-config --version | sed 's/^/cocotb /'), $(build/venv/bin/fusesoc --version 2>&1 | head -1 | sed 's/^/fusesoc /')"
