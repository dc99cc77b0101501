# %% [markdown]
# # A fragility curve on Dask
#
# The shipped fragility study (the paper's variable-friction wall, El Centro 1940 at six peak
# accelerations, 200 lognormal friction samples at each: 1,200 runs) on a Dask cluster, then the
# probability of collapse against the peak, with the lognormal curve pirqa fitted, drawn with
# matplotlib. Run it as a script (`python docs/python/fragility_dask.py [SWEEP] [OUT]` from the
# repository's root) or cell by cell in Jupyter or VS Code.

# %%
import json
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from dask.distributed import Client, LocalCluster

import pirqa

ROOT = Path(__file__).resolve().parents[2]
spec = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "walls/studies/fragility.ron"
out = Path(sys.argv[2]) if len(sys.argv) > 2 else ROOT / "out/fragility-dask"

# %% [markdown]
# On a laptop or one node, a local cluster of worker processes. On an HPC system, the same
# sweep goes to Slurm through dask-jobqueue (`pip install dask-jobqueue`): replace the cluster
# with
#
# ```python
# from dask_jobqueue import SLURMCluster
# cluster = SLURMCluster(cores=8, processes=8, memory="16GB", walltime="01:00:00")
# cluster.scale(jobs=4)   # 4 nodes x 8 worker processes
# ```
#
# The workers read the sweep file and the walls and records it names at the same paths: keep
# them on a shared file system.

# %%
if __name__ == "__main__":
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        cases = pirqa.sweep(spec, client.get_executor(), out=out, fresh=True)

    # %% [markdown]
    # `cases` is cases.csv as a DataFrame keyed by case id (the command line's columns); the
    # same folder holds results.json, where pirqa's maximum-likelihood fit is.

    # %%
    levels = cases.groupby(cases["pga_gal"].round(1))["collapsed"].agg(["mean", "size"])
    print(levels)
    fits = json.loads((out / "results.json").read_text()).get("fragility", [])

    # %%
    fig, ax = plt.subplots(figsize=(6, 4))
    samples = int(levels["size"].iloc[0])
    ax.plot(levels.index, levels["mean"], "o", label=f"observed ({samples} samples per level)")
    if fits:
        theta, beta = fits[0]["median_pga_gal"], fits[0]["beta"]
        print(f"median collapse PGA {theta:.0f} gal, dispersion {beta:.2f}")
        pga = [10.0 * k for k in range(1, 401)]
        curve = [0.5 * (1 + math.erf(math.log(a / theta) / (beta * math.sqrt(2)))) for a in pga]
        ax.plot(pga, curve, "-", label=f"lognormal fit: median {theta:.0f} gal, beta {beta:.2f}")
    else:
        print("no fragility curve: the collapses cannot determine one (results.json)")
    ax.set_xlabel("peak ground acceleration (gal)")
    ax.set_ylabel("probability of collapse")
    ax.set_title(cases["wall"].iloc[0])
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "fragility-matplotlib.png", dpi=120)
    fig.savefig(out / "fragility-matplotlib.svg")
    levels.to_csv(out / "fragility-levels.csv")
    print(f"chart: {out / 'fragility-matplotlib.svg'} (and .png), its data: fragility-levels.csv")
