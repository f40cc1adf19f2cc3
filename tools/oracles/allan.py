#!/usr/bin/env python3
"""Oracle values for the Allan-variance tests (crates/thermonav/tests/it/allan.rs).

Generated ONCE with: Python 3.11.7, numpy 2.4.6, scipy 1.17.1, allantools 2024.6.
Output: crates/thermonav/tests/data/allan.json. Run from the repository root, with the
shared data folder beside the repository (../shared/data).

Contents:
- edf_greenhall: allantools.edf_greenhall(alpha, d=2, m, N, overlapping=True,
  modified=False) over a grid that reaches every branch of Greenhall & Riley (2004)
  for unmodified variances (J <= 100 with finite and infinite m', the Table 2/3 asymptotes,
  and the m' = J_max / r branch). allantools raises for white PM with ceil(M/m) <= 2;
  those points are omitted (the Rust test checks them against an exact closed form).
- chi2_ppf: scipy.stats.chi2.ppf(p, edf).
- oadev_decade_nbs14: allantools.oadev(y, rate=1, data_type='freq', taus='decade') on the
  NBS14 1000-point frequency series (shared/data/allantools/nbs14).
"""
import json
import pathlib

import allantools
import numpy as np
import scipy.stats

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "data"
OUT = ROOT / "crates" / "thermonav" / "tests" / "data" / "allan.json"


def edf_grid():
    rows = []
    # (m, n_phase) pairs: small m with J <= 100, m with 3m > 100 but M small (m' = inf),
    # large r (tables), and r <= 3 with J > 100 (m' = J_max / r).
    pairs = [(1, 20), (1, 1001), (4, 1001), (8, 1001), (16, 1001), (33, 1001), (40, 1001),
             (100, 100000), (1000, 100000), (40, 150), (45, 150), (60, 200), (300, 1000),
             (400, 1000), (250, 1001), (2, 10), (20, 61), (1024, 19983), (4096, 19983)]
    for alpha in (2, 1, 0, -1, -2):
        for m, n in pairs:
            if 2 * m + 2 > n:
                continue
            try:
                edf = allantools.edf_greenhall(alpha=alpha, d=2, m=m, N=n,
                                               overlapping=True, modified=False)
            except NotImplementedError:
                continue
            rows.append({"alpha": alpha, "m": m, "n_phase": n, "edf": float(edf)})
    return rows


def chi2_grid():
    rows = []
    one_sigma_tail = (1.0 - scipy.special.erf(1 / np.sqrt(2))) / 2
    for p in (one_sigma_tail, 1 - one_sigma_tail, 0.025, 0.975, 0.5):
        for edf in (0.7, 1.0, 2.3, 5.22, 12.44, 34.6, 99.5, 100.0, 101.3, 1155.2, 28638.8, 2.9e5):
            rows.append({"p": p, "edf": edf, "quantile": float(scipy.stats.chi2.ppf(p, edf))})
    return rows


def oadev_decade_nbs14():
    y = np.loadtxt(SHARED / "allantools" / "nbs14" / "nbs14_1000_frequency.txt")
    taus, devs, _, ns = allantools.oadev(y, rate=1.0, data_type="freq", taus="decade")
    return {"m": [int(t) for t in taus], "n_terms": [int(n) for n in ns],
            "oadev": [float(d) for d in devs]}


def main():
    out = {
        "generator": "tools/oracles/allan.py; Python 3.11.7, numpy 2.4.6, scipy 1.17.1, allantools 2024.6",
        "edf_greenhall": edf_grid(),
        "chi2_ppf": chi2_grid(),
        "oadev_decade_nbs14": oadev_decade_nbs14(),
    }
    OUT.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
