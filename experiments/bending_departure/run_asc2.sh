#!/bin/bash
cd .
for n in asc_0.39_e8 asc_0.50_e16; do
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 NUMBA_NUM_THREADS=1 timeout 400 ../../.venv/bin/python ancf_slide_couple.py runs/$n.toml runs/$n.json > runs/$n.log 2>&1
  echo "$n $(date +%T) $(tail -1 runs/$n.log)"
done
