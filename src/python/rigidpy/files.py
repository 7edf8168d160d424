"""Writing beside or into a campaign cube without ever damaging it (the Python side of
src/campaign/output_lock.cpp and src/io/output_file.cpp):

- CubeLock: the cube's lock, CUBE.lock, held with flock exactly as the campaign holds it, so a
  store into the cube and a campaign (or a second store) exclude each other;
- campaign_state: whether a campaign is writing the cube now (its lock is held) or stopped
  before the end (its journal is still there);
- refuse_output_over_inputs: an output path that is one of the inputs (same device and inode,
  however spelled) is refused;
- write_output / private_temporary: outputs are written under a private temporary name (mkstemp
  in the output's directory) and renamed into place; a failure at any point, a full disk
  included, removes the temporary.
"""
import contextlib
import errno
import fcntl
import os
import signal
import tempfile


class OutputError(Exception):
    """Bad output or a locked cube: one line, exit 2 (callers turn it into their InputError)."""


class CubeLock:
    """flock(LOCK_EX | LOCK_NB) on CUBE.lock, the campaign's protocol: the file is created if
    missing, re-locked if its holder removed it meanwhile, and removed (while still held) on
    release. A lock held by anyone else is refused at once: waiting could last a whole campaign."""

    def __init__(self, cube):
        self.cube = cube
        self.path = cube + ".lock"
        self.fd = None

    def __enter__(self):
        while True:
            try:
                fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
            except OSError as e:
                raise OutputError(f"{self.path}: cannot create the lock file: {e.strerror}")
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as e:
                os.close(fd)
                if e.errno in (errno.EWOULDBLOCK, errno.EAGAIN):
                    raise OutputError(f"{self.path}: a campaign or another rigid command is writing {self.cube} (it "
                                      f"holds this lock); nothing stored: run again once it is done, or --no-store")
                if e.errno == errno.EINTR:
                    continue
                raise OutputError(f"{self.path}: cannot lock ({e.strerror})")
            try:
                same = os.stat(self.path).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if same:
                self.fd = fd
                return self
            os.close(fd)

    def __exit__(self, *exc):
        if self.fd is not None:
            with contextlib.suppress(OSError):
                os.unlink(self.path)
            os.close(self.fd)
            self.fd = None
        return False


def campaign_state(cube):
    """"running" when CUBE.lock is held (a campaign, or a store, writing the cube now), "stopped"
    when CUBE.journal exists (a campaign stopped before its end: its cells not run are still to
    come, and the journal may hold results the cube has not), else None."""
    lock = cube + ".lock"
    try:
        fd = os.open(lock, os.O_RDONLY | os.O_CLOEXEC)
    except OSError:
        fd = None
    if fd is not None:
        try:
            fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
        except OSError as e:
            if e.errno in (errno.EWOULDBLOCK, errno.EAGAIN):
                return "running"
        finally:
            os.close(fd)
    if os.path.exists(cube + ".journal"):
        return "stopped"
    return None


def same_file(a, b):
    try:
        sa, sb = os.stat(a), os.stat(b)
    except OSError:
        return False
    return (sa.st_dev, sa.st_ino) == (sb.st_dev, sb.st_ino)


def refuse_output_over_inputs(output, option, inputs):
    """OutputError when `output` is one of `inputs` (by device and inode, not by spelling), or
    is a lock, journal or temporary of one of them."""
    for i in inputs:
        if same_file(output, i):
            raise OutputError(f"{option} {output}: is the input {i}; choose another output file")
        for suffix in (".lock", ".journal", ".tmp"):
            if same_file(output, i + suffix) or os.path.abspath(output) == os.path.abspath(i + suffix):
                raise OutputError(f"{option} {output}: is the campaign's own {suffix[1:]} file of {i}; "
                                  f"choose another output file")


@contextlib.contextmanager
def _terminate_as_exception():
    """SIGTERM and SIGHUP raise SystemExit, so a killed store still removes its temporary."""
    def raise_exit(signum, _frame):
        raise SystemExit(128 + signum)
    saved = {s: signal.signal(s, raise_exit) for s in (signal.SIGTERM, signal.SIGHUP)}
    try:
        yield
    finally:
        for s, h in saved.items():
            signal.signal(s, h)


@contextlib.contextmanager
def private_temporary(path, mode=None):
    """A private temporary file beside `path` (mkstemp: unique per process) as a path; on normal
    exit it is flushed to disk and renamed over `path` (with `mode`, else 0666 less the umask),
    on any exception removed."""
    directory = os.path.dirname(os.path.abspath(path))
    with _terminate_as_exception():
        fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=directory)
        os.close(fd)
        try:
            yield tmp
            if mode is None:
                umask = os.umask(0)
                os.umask(umask)
                mode = 0o666 & ~umask
            os.chmod(tmp, mode)
            with open(tmp, "rb") as fh:
                os.fsync(fh.fileno())
            os.replace(tmp, path)
            dfd = os.open(directory, os.O_RDONLY)
            try:
                os.fsync(dfd)
            finally:
                os.close(dfd)
        finally:
            with contextlib.suppress(FileNotFoundError):
                os.remove(tmp)


def write_output(path, option, inputs, write):
    """`write(tmp_path)` fills a private temporary renamed over `path`; `path` must not be one of
    `inputs`."""
    refuse_output_over_inputs(path, option, inputs)
    try:
        with private_temporary(path) as tmp:
            write(tmp)
    except OSError as e:
        raise OutputError(f"{option} {path}: cannot write it ({e.strerror or e})")


@contextlib.contextmanager
def output_text(path, option, inputs, newline=None):
    """A text file opened for writing on a private temporary renamed over `path` when the block
    ends; `path` must not be one of `inputs`."""
    refuse_output_over_inputs(path, option, inputs)
    with private_temporary(path) as tmp:
        with open(tmp, "w", newline=newline) as fh:
            yield fh


def save_figure(fig, path, option, inputs, **kw):
    """matplotlib's savefig through a private temporary (the format from the file name)."""
    fmt = os.path.splitext(path)[1].lower().lstrip(".") or "png"
    write_output(path, option, inputs, lambda tmp: fig.savefig(tmp, format=fmt, **kw))
