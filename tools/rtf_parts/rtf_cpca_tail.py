#!/usr/bin/python3
"""What storing a CPCA's tail components in 8 bits would cost and buy (issue 14, README "CPCA: the
tail in 8 bits, session 15"). A measurement, offline, on one `rtf_cpca_time run` saved with
RTF_CPCA_SAVE=PREFIX (fp16 α, cluster ids, basis) and its X:

  rtf_cpca_tail.py PREFIX X_FILE COMPONENTS FROBENIUS [D]

D: floats per sample row of X (and per basis row), the run's proxies × 768 (16 × 16 directions × RGB,
xi.comp's (k·16+i)·48 + 3j + c); default 6144 (8 proxies, the runs in README).
FROBENIUS is the run's printed error (fp16, all components). Predicted error of a shape that keeps
the first k components in fp16 and the next ne' − k in 8 bits (cpca.hpp quantize):
  e² = e_run² + Σ_{j>ne'} ‖α_j‖² (truncation: the basis is orthonormal, so dropping component j adds
       its α energy) + ‖α̃ − α‖² (the tail α rounded to 8 bits, one scale per sample)
       + Σ_h Σ_j ‖α_hj‖² ‖Ẽ_hj − E_hj‖² (each 8-bit basis row's rounding, weighted by its α energy),
relative to ‖X‖². Bytes as cpca.hpp storedBytes."""
import sys
import numpy as np



def fail(where, what):  # bad input: one line naming the file and place, exit 2
    print(f'rtf_cpca_tail.py: {where}: {what}', file=sys.stderr)
    sys.exit(2)


if len(sys.argv) not in (5, 6):
    fail('arguments', f'{len(sys.argv) - 1} given (expected PREFIX X_FILE COMPONENTS FROBENIUS [D])')
pre, xfile = sys.argv[1], sys.argv[2]
try:
    ne, frob = int(sys.argv[3]), float(sys.argv[4])
    D = int(sys.argv[5]) if len(sys.argv) == 6 else 6144
except ValueError as e:
    fail('arguments', f'{e} (expected integer COMPONENTS and D, a number FROBENIUS)')
if ne <= 0:
    fail('COMPONENTS', f'{ne} (expected > 0)')
try:
    X = np.memmap(xfile, dtype=np.float32, mode='r')
    a_raw = np.fromfile(pre + '.alpha', dtype=np.float32)
    K = np.fromfile(pre + '.cluster', dtype=np.uint32)
    b_raw = np.fromfile(pre + '.basis', dtype=np.float32)
except (OSError, ValueError) as e:
    fail(xfile if 'X' not in locals() else pre, str(e))
if D <= 0 or X.size % D != 0:
    fail(f'{xfile}: size', f'{X.size} floats is not a whole number of rows of D = {D} (expected a multiple of D; '
         f'pass the run\'s proxies × 768 as D)')
N = X.size // D
if a_raw.size != N * ne:
    fail(pre + '.alpha', f'{a_raw.size} floats (expected N × COMPONENTS = {N} × {ne})')
if K.size != N or (N and int(K.max()) >= 1 << 16):
    fail(pre + '.cluster', f'{K.size} ids (expected N = {N}, each a small cluster index)')
nc = int(K.max()) + 1 if N else 0
if b_raw.size != nc * (ne + 1) * D:
    fail(pre + '.basis', f'{b_raw.size} floats (expected clusters × (COMPONENTS + 1) × D = {nc} × {ne + 1} × {D}; '
         'a wrong D or COMPONENTS)')
nx2 = float(sum(np.dot(c.astype(np.float64), c.astype(np.float64)) for c in np.array_split(np.asarray(X), 64)))
A = a_raw.reshape(-1, ne).astype(np.float64)
B = b_raw.reshape(-1, ne + 1, D).astype(np.float64)
err2 = frob ** 2 * nx2


def rowq(M, axis_max):  # 8-bit codes with one scale = max|row| / 127 per row
    m = np.abs(M).max(axis=axis_max, keepdims=True)
    s = np.where(m > 0, m / 127.0, 1.0)
    return np.round(M / s) * s


Ehj = np.array([(A[K == h] ** 2).sum(axis=0) for h in range(nc)])  # α energy per cluster, component
dB = np.array([((rowq(B[h, 1:], 1) - B[h, 1:]) ** 2).sum(axis=1) for h in range(nc)])
tail = np.concatenate([np.cumsum(Ehj.sum(axis=0)[::-1])[::-1], [0.0]])
# α all in 8 bits with one scale per (cluster, component) column, against one per sample:
col = sum(((rowq(A[K == h], 0) - A[K == h]) ** 2).sum() for h in range(nc))
row = ((rowq(A, 1) - A) ** 2).sum()
print(f'all alpha 8-bit, basis fp16: per-component scale {np.sqrt((err2 + col) / nx2):.4f}, '
      f'per-sample scale {np.sqrt((err2 + row) / nx2):.4f} (fp16: {frob:.4f})')
for k in (0, 8, 16, 24, 32):
    for nep in (96, 104, 112, 120, 128):
        if nep > ne or nep < k:
            continue
        by = 2 * (nc * D * (1 + k) + N * k) + nc * D * (nep - k) + N * (nep - k) + 4 * (nc * (nep - k) + N) + 4 * N
        Aq = A[:, :nep].copy()
        Aq[:, k:] = rowq(A[:, k:nep], 1)
        na = ((Aq - A[:, :nep]) ** 2).sum()
        nb = (Ehj[:, k:nep] * dB[:, k:nep]).sum()
        print(f'fp16 head k={k} ne={nep} ratio={4.0 * N * D / by:.1f} -> frobenius {np.sqrt((err2 + tail[nep] + na + nb) / nx2):.4f}')
