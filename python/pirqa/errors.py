"""pirqa's exceptions. Every error pirqa raises is a ``PirqaError``; those about what was given
(a wall, a motion, a sweep file, an option) are also ``ValueError``, those about files also
``OSError``. The message is the command line's: it names the file, the line or the block, and
what to fix."""


class PirqaError(Exception):
    """Root of pirqa's exceptions."""


class WallError(PirqaError, ValueError):
    """A wall file, RON text or set of rectangles that is malformed or describes an impossible
    wall (a floating block, overlapping blocks, a friction key that names no joint)."""


class MotionError(PirqaError, ValueError):
    """A ground motion that cannot be used (a bad record file, NaN samples, an absurd time step,
    a value without units)."""


class SweepError(PirqaError, ValueError):
    """A sweep file that is malformed or names files that cannot be read."""


class OptionError(PirqaError, ValueError):
    """An argument out of range, or arguments that do not go together."""


class SimulationError(PirqaError):
    """A run that could not go on (its message says where and why)."""


class FileError(PirqaError, OSError):
    """A file that could not be read or written (with what to do: a full disk, a folder that
    cannot be written)."""


class ResultsError(PirqaError):
    """Results read back (a sweep's tables, its parts) that are malformed or do not belong
    together."""


__all__ = [
    "PirqaError",
    "WallError",
    "MotionError",
    "SweepError",
    "OptionError",
    "SimulationError",
    "FileError",
    "ResultsError",
]
