"""The exceptions probrobscene raises for bad programs and impossible scenarios.

Kept apart from ``__init__`` so the C++ extension can raise them without importing the package
itself (the extension is imported while the package is being initialised).
"""

from typing import Optional


class ScenarioError(Exception):
    """A scenario could not be compiled or run.

    Attributes:
        message: The first error's message, e.g. "unknown name 'Cueb'".
        id: Its stable diagnostic id, e.g. "unknown-name" (see docs/diagnostics.md).
        file: The file it is in (for ``loads``, the ``name`` given), or None.
        line: 1-based line of the error, or None when it has no location.
        column: 1-based column (in code points), or None.
        text: Every error rendered as ``prs`` prints it: ``file:line:col: error: ...``,
            the source line and a caret. ``str(error)`` is this text.
    """

    def __init__(self, message: str, *, id: str = "", file: Optional[str] = None,
                 line: Optional[int] = None, column: Optional[int] = None,
                 text: Optional[str] = None) -> None:
        super().__init__(message)
        self.message = message
        self.id = id
        self.file = file
        self.line = line
        self.column = column
        self.text = text if text else message

    def __str__(self) -> str:
        return self.text.rstrip("\n")


class SamplingError(ScenarioError):
    """No valid scene was found within ``max_attempts`` (``prs sample`` exits with code 3).

    The message names the most frequent reason for rejection and the counts.
    """
