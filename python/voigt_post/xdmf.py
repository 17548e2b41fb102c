"""The outputs listed in a run's fields.xdmf (Python standard library only).

Voigt's writer (src/io/) lists one uniform grid per output, its HDF5 file, time, node counts,
origin and spacing, in XDMF's z y x order. Every case script reads them here, in x y z order:

    from voigt_post.xdmf import frames   # python/README.md: how voigt_post is installed
    for f in frames("output/run"):  # f.t, f.path, f.cells, f.origin, f.spacing (x y z)
"""
import collections
import os
import re

Frame = collections.namedtuple("Frame", "t path cells origin spacing")

_GRID = re.compile(r'<Grid Name="(fields_\d+\.h5)" GridType="Uniform">(.*?)</Grid>', re.S)


def _item(body, pattern):
    m = re.search(pattern, body)
    if m is None:
        raise ValueError("fields.xdmf: a grid without %s" % pattern)
    return m.group(1)


def _xyz(text, conv):
    return [conv(v) for v in text.split()][::-1]


def frames(outdir, upto=None):
    """Every output of OUTDIR in the order written (time order), or those at or before `upto`
    (seconds); an error if there are none."""
    path = os.path.join(outdir, "fields.xdmf")
    with open(path) as f:
        text = f.read()
    out = []
    for g in _GRID.finditer(text):
        body = g.group(2)
        t = float(_item(body, r'<Time Value="([^"]+)"'))
        if upto is not None and t > upto + 1e-9:
            continue
        nodes = _xyz(_item(body, r'3DCoRectMesh" Dimensions="([^"]+)"'), int)
        out.append(Frame(t, os.path.join(outdir, g.group(1)), [n - 1 for n in nodes],
                         _xyz(_item(body, r'Name="Origin"[^>]*>([^<]+)<'), float),
                         _xyz(_item(body, r'Name="Spacing"[^>]*>([^<]+)<'), float)))
    if not out:
        raise ValueError("%s lists no outputs%s" % (path, "" if upto is None else " at or before t = %g s" % upto))
    return out
