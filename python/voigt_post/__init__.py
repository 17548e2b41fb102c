"""Voigt's analysis package: read a run, launch voigt, the shared formulas, pictures. Every case
script (cases/) and perf study (perf/) reads runs and launches voigt through it.

How a script finds it (no install, no .pth): one line puts the repository's python/ folder first
on sys.path, counted up from the script's real location (links resolved), e.g. in cases/<case>/:

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "..", "python"))  # voigt_post
    from voigt_post import fields, series  # noqa: E402

or from a shell: PYTHONPATH=python /usr/bin/python3 -m voigt_post.picture ...

Modules (standard library only unless said):
- xdmf: the outputs a run listed in fields.xdmf (time, file, cells, origin, spacing);
- fields: the datasets of an HDF5 output as numpy arrays (h5py, else h5dump);
- series: summary.json, timeseries.csv, probe_<name>.csv; CSV tables of the studies;
- scene_record: the scene a run used (scene.yaml in its output; PyYAML);
- launch: the `voigt run` command line (mpirun --allow-run-as-root --oversubscribe for ranks > 1),
  runs in their own process group with a time limit, the repository root;
- formulas: the smoothed Heaviside of Eq. (4), the Taylor-Green vortex and its error (numpy);
- couette: the elastic Couette flow's exact periodic state and its smoothed-interface model (numpy, scipy);
- report: number formats, medians and README sections for the perf reports;
- picture: the level set's surface coloured by stress, one panel per run and time (VTK, h5py);
  `scripts/picture` runs it from the command line.
Tests: python/tests (unittest; CTest's python.voigt_post, run by scripts/test).
"""
