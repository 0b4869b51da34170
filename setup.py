"""Package discovery, the one thing pyproject.toml cannot say: every subpackage of sdfgl/ is
found automatically, plus ``sdfgl.shaders``, whose folder (shaders/, mapped in pyproject.toml's
package-dir) lies outside sdfgl/ and so is invisible to setuptools' finder."""
from setuptools import find_packages, setup

setup(packages=find_packages(include=["sdfgl", "sdfgl.*"]) + ["sdfgl.shaders"])
