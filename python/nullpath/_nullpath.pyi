"""Type stubs of the Rust extension module ``nullpath._nullpath``."""

__version__: str
