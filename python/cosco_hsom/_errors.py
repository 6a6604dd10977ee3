"""Exceptions for files that could not be read or written. Each is both the matching
``OSError`` subclass and a ``ValueError``, so ``except ValueError`` catches every refusal of
bad input (a missing configuration file included) and ``except FileNotFoundError`` works as
usual. Their message is the one the ``cosco`` command-line tool prints."""


class MissingFileError(FileNotFoundError, ValueError):
    """A file that does not exist."""


class FileAccessError(PermissionError, ValueError):
    """A file that may not be read or written."""


class FileError(OSError, ValueError):
    """Any other failure to read or write a file."""
