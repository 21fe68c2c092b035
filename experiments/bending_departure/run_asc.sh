#!/bin/bash
cd .
for x in 0.39 0.35 0.45; do
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 NUMBA_NUM_THREADS=1 timeout 480 ../../.venv/bin/python ancf_slide_couple.py runs/asc_${x}_e16.toml runs/asc_${x}_e16.json > runs/asc_${x}_e16.log 2>&1
  echo "$x $(date +%T) $(tail -1 runs/asc_${x}_e16.log)"
done
