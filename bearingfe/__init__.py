"""bearingfe: finite-element Reynolds solver for bearing supports with inlet pockets."""

__version__ = "0.1.0"
