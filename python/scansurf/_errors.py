"""The exceptions of scansurf: one class per error category of the library (scansurf/result.h).

Every error the library reports is raised as one of these, with the library's message: the file,
feature, slice and contour at fault. Each also derives from the built-in exception a Python user
would catch for it (ValueError, OSError, MemoryError, RuntimeError).
"""


class Error(Exception):
    """Any error scansurf reports."""

    code = 0
    exit_code = 0  # the command-line tool's exit code for the same error


def _category(name, code, base, doc):
    cls = type(name, (Error, base), {"__doc__": doc, "code": code, "exit_code": code + 1})
    cls.__module__ = "scansurf"
    return cls


InvalidArgument = _category("InvalidArgument", 1, ValueError, "An option or parameter out of range.")
InvalidInput = _category("InvalidInput", 2, ValueError, "The input is malformed or inconsistent.")
IoError = _category("IoError", 3, OSError, "A file could not be read or written.")
NoDevice = _category("NoDevice", 4, RuntimeError, "No usable Vulkan device.")
VulkanError = _category("VulkanError", 5, RuntimeError, "A Vulkan call failed.")
InternalError = _category("InternalError", 6, RuntimeError, "A broken invariant: a bug in scansurf.")
OutOfMemory = _category("OutOfMemory", 7, MemoryError, "A host or device allocation failed.")
ResourceLimit = _category("ResourceLimit", 8, MemoryError,
                          "Refused before starting: the run would need more memory than allowed.")
DefectiveSurface = _category("DefectiveSurface", 9, RuntimeError,
                             "A surface came out open, not manifold or not oriented; nothing is kept.")

__all__ = ["Error", "InvalidArgument", "InvalidInput", "IoError", "NoDevice", "VulkanError",
           "InternalError", "OutOfMemory", "ResourceLimit", "DefectiveSurface"]
