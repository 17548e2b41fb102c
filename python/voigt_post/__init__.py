"""Voigt's analysis package: read a run (fields.xdmf frames, the scene record) and draw it.

Put this folder's parent (`python/`) on sys.path or PYTHONPATH. Modules:
- xdmf: the outputs a run listed in fields.xdmf (standard library only);
- scene_record: the scene a run used (scene.yaml in its output; PyYAML);
- picture: the level set's surface coloured by stress, one panel per run and time (VTK, h5py).
`scripts/picture` runs voigt_post.picture from the command line.
"""
