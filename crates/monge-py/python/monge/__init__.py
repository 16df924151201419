"""monge: exact circular and conical quad meshes with planar curvature lines.

Python bindings of the monge library, which implements X. Tellier, C. Douthe,
L. Hauswirth, O. Baverel, "Surfaces with planar curvature lines:
discretization, generation and application to the rationalization of curved
architectural envelopes", Automation in Construction 106 (2019) 102880
(section numbers in the docstrings are the paper's).

    >>> import monge
    >>> design = monge.Design.from_file("examples/fig12-dupin-theta30.json")
    >>> mesh = monge.generate(design)
    >>> mesh.vertices.shape          # (rows, cols, 3), float64, no copy
    (41, 33, 3)

Every error is a ``monge.MongeError`` (``DesignError``, ``ThetaError``, ...)
whose message is the one the ``monge`` command prints; its warnings are
Python warnings (``monge.FarFromOriginWarning``, ``monge.InexactWarning``, both
``UserWarning``). Optional modules:
``monge.rhino`` (Rhino .3dm files, needs rhino3dm) and ``monge.compas``
(COMPAS meshes, needs compas).
"""

from ._monge import (
    DegenerateError,
    Design,
    DesignError,
    FabricationError,
    FarFromOriginWarning,
    FileError,
    InexactWarning,
    Mesh,
    MeshError,
    MongeError,
    OptimiseError,
    PatchesDesign,
    TrimmedDesign,
    ScanError,
    SmoothError,
    ThetaError,
    __version__,
    approximate,
    check,
    fabricate,
    fit,
    generate,
    info,
    optimise_panels,
    scan,
    smooth,
    target_points,
)

__all__ = [
    "DegenerateError",
    "Design",
    "DesignError",
    "FabricationError",
    "FarFromOriginWarning",
    "FileError",
    "InexactWarning",
    "Mesh",
    "MeshError",
    "MongeError",
    "OptimiseError",
    "PatchesDesign",
    "TrimmedDesign",
    "ScanError",
    "SmoothError",
    "ThetaError",
    "__version__",
    "approximate",
    "check",
    "fabricate",
    "fit",
    "generate",
    "info",
    "optimise_panels",
    "scan",
    "smooth",
    "target_points",
]
