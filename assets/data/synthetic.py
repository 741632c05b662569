"""Writes synthetic-strings.csv: SYNTHETIC data, not a measurement.

omega2 from the model (`snapback sweep`, the binary on PATH) at the paper's Fig. 3(c) values with a 5 g
cart on 12 kN/m and mu = 0.35, at angles 20 to 80 deg and incident spins 0 and -100 rad/s, plus normal
noise of standard deviation 3 rad/s from Python's random.Random(14), rounded to 0.1 rad/s.
Run from the repository: python3 assets/data/synthetic.py > assets/data/synthetic-strings.csv
"""

import csv
import io
import random
import subprocess

TRUTH = ["--cart-mass", "5g", "--stiffness", "12kN/m", "--mu", "0.35"]
SIGMA = 3.0

rng = random.Random(14)
print("# SYNTHETIC data made by assets/data/synthetic.py, not a measurement: omega2 of the model at")
print("# Fig. 3(c) with cart-mass 5 g, stiffness 12 kN/m, mu 0.35, plus normal noise sigma 3 rad/s (seed 14)")
print("angle,spin,omega2,sigma_omega2")
for spin in ["0", "-100"]:
    sweep = subprocess.run(
        ["snapback", "sweep", "--vary", "angle", "--from", "20", "--to", "80", "--steps", "7", "--spin", spin]
        + TRUTH,
        capture_output=True, text=True, check=True,
    ).stdout
    for row in csv.DictReader(io.StringIO(sweep)):
        omega2 = float(row["omega2"]) + rng.gauss(0.0, SIGMA)
        print(f"{float(row['angle_deg']):g},{spin},{omega2:.1f},{SIGMA:g}")
