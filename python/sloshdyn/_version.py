"""The version, set once in meson.build's project() and installed with the package's metadata;
here, at the bottom of the package, so that any module can name it without importing the
package (docs/architecture.md, "Python layers")."""

from importlib.metadata import version

__version__ = version("sloshdyn")
