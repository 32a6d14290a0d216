"""Output files written whole or not at all, with the user's normal permissions.

Every file the plugin writes goes first to a temporary name beside its destination (same
folder, so the final ``os.replace`` is atomic) and is renamed only when it is complete; on
failure or cancel the temporary file is removed and the destination is left as it was.
``tempfile.mkstemp`` creates files readable by their owner only (0600): before the rename
they get the mode a plain ``open()`` would have given them, ``0666`` less the umask
(:func:`default_file_mode`), so that a colleague or a web server can read them.

:class:`StagedOutputs` does this for a group of outputs of one run (files and folders):
each is written under its temporary name, and :meth:`StagedOutputs.commit` moves them all
into place at the end, or :meth:`StagedOutputs.rollback` removes them all.
"""
from __future__ import annotations

import os
import shutil
import tempfile
from contextlib import contextmanager
from typing import Iterator, List, Tuple

from .errors import InputError

#: prefix of every temporary output name (hidden on Unix)
TEMP_PREFIX = ".roadsigns-"


def current_umask() -> int:
    """The process umask (read from /proc where possible: setting it is not thread safe)."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def default_file_mode() -> int:
    """The permissions ``open(path, "w")`` gives a new file: 0666 less the umask."""
    return 0o666 & ~current_umask()


def default_folder_mode() -> int:
    """The permissions ``os.mkdir`` gives a new folder: 0777 less the umask."""
    return 0o777 & ~current_umask()


def set_default_mode(path: str) -> None:
    """Give ``path`` (a file, or a folder and everything in it) the umask's permissions."""
    if os.path.isdir(path) and not os.path.islink(path):
        os.chmod(path, default_folder_mode())
        for root, folders, files in os.walk(path):
            for name in folders:
                os.chmod(os.path.join(root, name), default_folder_mode())
            for name in files:
                os.chmod(os.path.join(root, name), default_file_mode())
    else:
        os.chmod(path, default_file_mode())


def _folder_of(path: str) -> str:
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise InputError("Cannot write {path}: the folder {folder} does not exist", path=path, folder=folder)
    return folder


def temp_path_beside(path: str) -> str:
    """A new empty file beside ``path`` with a hidden temporary name ending like ``path``
    (``.roadsigns-XXXX-signs.laz``), created here so that the name is the caller's."""
    folder = _folder_of(path)
    try:
        handle, temporary = tempfile.mkstemp(prefix=TEMP_PREFIX, suffix="-" + os.path.basename(path),
                                             dir=folder)
    except OSError as e:
        raise InputError("Cannot write {path}: {error}", path=path, error=e.strerror or str(e))
    os.close(handle)
    return temporary


def temp_folder_beside(path: str) -> str:
    """A new empty folder beside ``path`` with a hidden temporary name."""
    folder = _folder_of(path)
    try:
        return tempfile.mkdtemp(prefix=TEMP_PREFIX, suffix="-" + os.path.basename(os.path.normpath(path)),
                                dir=folder)
    except OSError as e:
        raise InputError("Cannot write {path}: {error}", path=path, error=e.strerror or str(e))


def remove(path: str) -> bool:
    """Remove a file or folder if it is there; False when it could not be removed."""
    try:
        if os.path.isdir(path) and not os.path.islink(path):
            shutil.rmtree(path)
        elif os.path.lexists(path):
            os.remove(path)
    except OSError:
        return False
    return True


def move_into_place(temporary: str, path: str) -> None:
    """Give ``temporary`` the umask's permissions and rename it to ``path`` (replacing it).

    A folder that exists at ``path`` is replaced as a whole: it is moved aside first and
    removed once the new one is in place.
    """
    set_default_mode(temporary)
    if os.path.isdir(temporary) and os.path.isdir(path) and not os.path.islink(path):
        old = tempfile.mkdtemp(prefix=TEMP_PREFIX + "old-", dir=os.path.dirname(os.path.abspath(path)))
        os.rmdir(old)
        os.rename(path, old)
        try:
            os.rename(temporary, path)
        except BaseException:
            os.rename(old, path)
            raise
        remove(old)
    else:
        os.replace(temporary, path)


@contextmanager
def atomic_file(path: str) -> Iterator[str]:
    """``with atomic_file(path) as temporary:`` write ``temporary``; on leaving the block it
    replaces ``path`` with the umask's permissions, or is removed if the block raised."""
    temporary = temp_path_beside(path)
    try:
        yield temporary
        move_into_place(temporary, path)
    except BaseException:
        remove(temporary)
        raise


def write_text_atomically(path: str, text: str) -> None:
    """Write ``text`` (UTF-8, ``\\n`` line ends) to ``path`` whole or not at all."""
    folder = os.path.dirname(os.path.abspath(path))
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as e:
        raise InputError("Cannot write {path}: {error}", path=path, error=e.strerror or str(e))
    with atomic_file(path) as temporary:
        with open(temporary, "w", encoding="utf-8", newline="\n") as stream:
            stream.write(text)


class StagedOutputs:
    """The outputs of one run, each written under a temporary name beside its destination.

    ``file(path)`` / ``folder(path)`` return the temporary name to write to; ``commit()``
    moves every one into place (with the umask's permissions); ``rollback()`` removes them
    and returns the temporary names it could not remove.
    """

    def __init__(self) -> None:
        self._staged: List[Tuple[str, str]] = []  # (temporary, destination)
        self._made: List[str] = []  # folders made for the outputs, removed again on rollback

    def __len__(self) -> int:
        return len(self._staged)

    def _make_folder_of(self, path: str) -> None:
        """Make the missing folders of ``path`` (as a plain write would need them)."""
        missing, folder = [], os.path.dirname(os.path.abspath(path))
        while folder and not os.path.exists(folder) and os.path.dirname(folder) != folder:
            missing.append(folder)
            folder = os.path.dirname(folder)
        for folder in reversed(missing):
            try:
                os.mkdir(folder)
            except OSError as e:
                raise InputError("Cannot write {path}: {error}", path=path, error=e.strerror or str(e))
            self._made.append(folder)

    def file(self, path: str) -> str:
        self._make_folder_of(path)
        temporary = temp_path_beside(path)
        os.remove(temporary)  # writers create it (some refuse an existing file); the name stays ours
        self._staged.append((temporary, os.path.abspath(path)))
        return temporary

    def folder(self, path: str) -> str:
        self._make_folder_of(path)
        temporary = temp_folder_beside(path)
        self._staged.append((temporary, os.path.abspath(path)))
        return temporary

    def destination(self, temporary: str) -> str:
        for staged, path in self._staged:
            if staged == temporary:
                return path
        raise KeyError(temporary)

    def commit(self) -> None:
        """Move every staged output into place; one that was not written is an error."""
        for temporary, path in self._staged:
            if not os.path.lexists(temporary):
                raise InputError("The output {path} was not written", path=path)
        try:
            for temporary, path in self._staged:
                move_into_place(temporary, path)
        except OSError as e:
            raise InputError("Cannot write {path}: {error}", path=path, error=e.strerror or str(e))
        self._staged, self._made = [], []

    def rollback(self) -> List[str]:
        left = [temporary for temporary, _ in self._staged if not remove(temporary)]
        for folder in reversed(self._made):
            try:
                os.rmdir(folder)  # only if empty: never what someone else put there
            except OSError:
                pass
        self._staged, self._made = [], []
        return left
