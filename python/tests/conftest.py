"""Shared fixtures of the Python package's tests (run by ctest, see python/CMakeLists.txt):
the package from the build tree, with the Vulkan validation layers on (SCANSURF_VALIDATION=1, set
by ctest; a validation message makes build() raise VulkanError)."""

import os
import pathlib
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))

import scansurf  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "phantom.json"


@pytest.fixture(scope="session")
def phantom():
    return scansurf.read(EXAMPLE)


@pytest.fixture(scope="session")
def phantom_result(phantom):
    return scansurf.build(phantom)


def sphere(radius=10.0, spacing=2.0, n=40):
    import numpy as np
    slices = {}
    for k in range(-int(radius // spacing), int(radius // spacing) + 1):
        z = k * spacing
        r = (radius ** 2 - z ** 2) ** 0.5
        if r > 0.5:
            t = np.linspace(0, 2 * np.pi, n, endpoint=False)
            slices[z] = [np.stack([r * np.cos(t), r * np.sin(t)], axis=1)]
    return slices


@pytest.fixture
def cli():
    path = os.environ.get("SCANSURF_CLI")
    if not path:
        pytest.skip("SCANSURF_CLI is not set (ctest sets it to the built command-line tool)")
    return path
