"""Voigt's analysis package: read a run, launch voigt, the shared formulas, pictures. Every case
script (cases/) and perf study (perf/) reads runs and launches voigt through it.

How a script finds it: as an installed package, `from voigt_post import fields, series`, with
no sys.path edits. scripts/setup writes a voigt.pth naming the checkout's python/ folder into
/usr/bin/python3's site-packages (Debian's python3 is externally managed, PEP 668: no pip);
in a virtual environment `pip install -e python` (python/pyproject.toml); for one command
PYTHONPATH=python /usr/bin/python3 ... (python/README.md).

Modules (standard library only unless said):
- xdmf: the outputs a run listed in fields.xdmf (time, file, cells, origin, spacing);
- fields: the datasets of an HDF5 output as numpy arrays (h5py, else h5dump);
- series: summary.json, timeseries.csv, probe_<name>.csv; CSV tables of the studies;
- scene_record: the scene a run used (scene.yaml in its output; PyYAML), and its numbers
  (domain, spacing, materials, level sets) for the case scripts, which keep no copies;
- launch: the `voigt run` command line (mpirun --allow-run-as-root --oversubscribe for ranks > 1),
  runs in their own process group with a time limit, the repository root;
- formulas: the smoothed Heaviside of Eq. (4), the Taylor-Green vortex and its error (numpy);
- couette: the elastic Couette flow's exact periodic state and its smoothed-interface model (numpy, scipy);
- report: number formats, medians and README sections for the perf reports and the cases' tables;
- ledger, run_ids: a study's run ledger (runs.csv) and run ids (cases/runs.py is their command line);
- ergun: Ergun's gradient through a rigid bed (paper Eq. 23) with the porous bed scene's gas;
- porous_bed: what the porous bed's figures read from a run folder or its digest (numpy);
- picture: the level set's surface coloured by stress, one panel per run and time (VTK, h5py);
  `scripts/picture` runs it from the command line.
Tests: python/tests (unittest; CTest's python.voigt_post, run by scripts/test), the modules and
every case script on tiny runs.
"""
