#!/usr/bin/python3
"""How strongly a beam's damping couples its modes (issue 16: can a structured eigen-solution beat dense QR?).

    /usr/bin/python3 tools/damping_coupling.py [--beamid build/beamid] [BEAM ...]

For each beam (presets by default) and N = 8, 16, 32, with the Galerkin matrices from `beamid system`: the undamped
modes (K phi = w^2 M phi), the damping in their basis c_jk = phi_j^T C phi_k, each mode's decoupled poles mu from
mu^2 + c_jj mu + w_j^2 = 0, and the first-order coupling ratio of pole mu_j to mode k,
    r = |mu_j c_jk| / sqrt(|2 mu_j + c_jj| |mu_j^2 + c_kk mu_j + w_k^2|),
the size of the perturbation it causes relative to the gap. Poles joined by r above a threshold (or a mode's two poles
closer than 10 %) form clusters; a scheme of perturbation plus dense solves of the clusters costs about the sum of
the clusters' cubes, printed relative to the dense (2n)^3. Measured 2026-11-25: banks-aluminium decouples (no cluster
at 0.1), thick-steel is one cluster of nearly every pole (its kAcs/kAG and cDI/EI differ 10x).
"""
import argparse
import json
import subprocess

import numpy as np
import scipy.linalg
import scipy.sparse.csgraph


def coupling(beamid, beam, elements):
    s = json.loads(subprocess.run([beamid, "system", "--beam", beam, "--elements", str(elements)],
                                  capture_output=True, text=True, check=True).stdout)
    m, c, k = (np.array(s[key]) for key in "MCK")
    w2, phi = scipy.linalg.eigh(k, m)
    d = phi.T @ c @ phi
    n = len(w2)
    mu = np.array([np.roots([1.0, d[j, j], w2[j]]) for j in range(n)])
    r = np.zeros((2 * n, 2 * n))
    for j in range(n):
        for a in range(2):
            p = mu[j, a]
            for q in range(n):
                if q != j:
                    ratio = abs(p * d[j, q]) / np.sqrt(abs(2 * p + d[j, j]) * abs(p * p + d[q, q] * p + w2[q]))
                    r[2 * j + a, 2 * q] = r[2 * j + a, 2 * q + 1] = ratio
    return mu, r


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--beamid", default="build/beamid")
    parser.add_argument("beams", nargs="*", default=["banks-aluminium", "thick-steel"])
    args = parser.parse_args()
    print("beam,N,poles,threshold,largest_cluster,clusters,cost_vs_dense")
    for beam in args.beams:
        for elements in (8, 16, 32):
            mu, r = coupling(args.beamid, beam, elements)
            n = len(mu)
            for threshold in (0.1, 0.01):
                joined = (r > threshold) | (r.T > threshold)
                for j in range(n):
                    if abs(mu[j, 0] - mu[j, 1]) < 0.1 * abs(mu[j, 0]):
                        joined[2 * j, 2 * j + 1] = joined[2 * j + 1, 2 * j] = True
                _, label = scipy.sparse.csgraph.connected_components(joined, directed=False)
                sizes = np.bincount(label).astype(float)
                print(f"{beam},{elements},{2 * n},{threshold},{int(sizes.max())},{int(np.sum(sizes > 1))},"
                      f"{np.sum(sizes**3) / (2 * n)**3:.3f}")


if __name__ == "__main__":
    main()
