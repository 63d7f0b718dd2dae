"""make install puts the workbench in FreeCAD's Mod directory, whole (with
its copy of the Python client's modules); make freecad-link makes the checkout's the
one FreeCAD loads; make uninstall removes what install put.  Each is then
loaded by a FreeCAD of its own (freecadcmd) and asked where it found the
modules."""

import os
import shutil
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
PROBE = ("import FreeCAD, wrench_freecad, wrenchd; "
         "print('FOUND', wrench_freecad.__file__, wrenchd.__file__, "
         "FreeCAD.getUserAppDataDir())")


def freecadcmd(*args, home):
    env = dict(os.environ, HOME=str(home))
    env.pop("PYTHONPATH", None)
    proc = subprocess.run([shutil.which("freecadcmd") or "freecadcmd"] + list(args), env=env,
                          cwd=str(home), stdin=subprocess.DEVNULL, capture_output=True,
                          timeout=120)
    out = proc.stdout.decode(errors="replace")
    found = [line.split()[1:] for line in out.splitlines() if line.startswith("FOUND ")]
    assert proc.returncode == 0 and found, out + proc.stderr.decode(errors="replace")
    return found[0]


def make(*args):
    proc = subprocess.run(["make", "-C", REPO, "--no-print-directory"] + list(args),
                          stdin=subprocess.DEVNULL, capture_output=True, timeout=300)
    assert proc.returncode == 0, proc.stdout.decode() + proc.stderr.decode()
    return proc.stdout.decode()


def test_make_install_and_uninstall(tmp_path):
    """The default PREFIX (/usr/local): into the Mod directory of the FreeCAD
    running this test (FreeCAD.getResourceDir()), whatever the prefix."""
    import FreeCAD
    destdir = tmp_path / "root"
    moddir = FreeCAD.getResourceDir() + "Mod"
    make("install", "DESTDIR=%s" % destdir)
    workbench = destdir / moddir.lstrip("/") / "Wrench"
    names = sorted(str(p.relative_to(workbench)) for p in workbench.rglob("*") if p.is_file())
    icons = sorted("Resources/icons/" + f
                   for f in os.listdir(os.path.join(REPO, "clients", "freecad", "Resources", "icons")))
    assert names == sorted(["Init.py", "InitGui.py", "wrench_commands.py", "wrench_freecad.py",
                            "wrench_outline.py", "wrench_objects.py", "wrench_view.py",
                            "wrench_supports.py", "wrenchd.py", "wrenchd_arcs.py"] + icons)
    # the same files as the checkout's
    for name in names:
        client_side = name in ("wrenchd.py", "wrenchd_arcs.py")
        source = os.path.join(REPO, "clients", "python" if client_side else "freecad", name)
        with open(source, "rb") as a, open(workbench / name, "rb") as b:
            assert a.read() == b.read(), name
    # FreeCAD loads it from there, the client too (not from the checkout)
    home = tmp_path / "home"
    home.mkdir()
    module, client, _ = freecadcmd("-c", PROBE, "-M", str(workbench), home=home)
    assert module == str(workbench / "wrench_freecad.py")
    assert client == str(workbench / "wrenchd.py")
    make("uninstall", "DESTDIR=%s" % destdir)
    assert not workbench.exists()
    assert [p for p in destdir.rglob("*") if p.is_file()] == []


def test_make_install_for_a_user(tmp_path):
    """PREFIX=~/.local: into ~/.local/share/FreeCAD/Mod, FreeCAD 0.20's user
    Mod directory, where a FreeCAD of that home finds it at start.  (Staged
    in DESTDIR, the home inside it; SYSCONFDIR kept as built, so that
    build/wrenchd is not rebuilt for another configuration path.)"""
    destdir = tmp_path / "root"
    home = destdir / "home" / "user"
    args = ["DESTDIR=%s" % destdir, "PREFIX=/home/user/.local", "SYSCONFDIR=/usr/local/etc"]
    before = os.stat(os.path.join(REPO, "build", "wrenchd")).st_mtime_ns
    make("install", *args)
    assert os.stat(os.path.join(REPO, "build", "wrenchd")).st_mtime_ns == before
    workbench = home / ".local" / "share" / "FreeCAD" / "Mod" / "Wrench"
    assert (workbench / "InitGui.py").is_file() and (workbench / "wrenchd.py").is_file()
    assert (workbench / "wrenchd_arcs.py").is_file()
    module, client, userdir = freecadcmd("-c", PROBE, home=home)
    assert userdir == str(home / ".local" / "share" / "FreeCAD") + "/"
    assert module == str(workbench / "wrench_freecad.py")
    assert client == str(workbench / "wrenchd.py")
    make("uninstall", *args)
    assert not workbench.exists()


def test_make_freecad_link(tmp_path):
    """The checkout's workbench, linked into FreeCAD's user Mod directory, is
    what a FreeCAD started with that HOME loads (and its client the
    checkout's clients/python/wrenchd.py)."""
    home = tmp_path / "home"
    home.mkdir()
    make("freecad-link", "HOME=%s" % home)
    link = home / ".local" / "share" / "FreeCAD" / "Mod" / "Wrench"
    assert link.is_symlink() and os.path.realpath(link) == os.path.join(REPO, "clients", "freecad")
    module, client, userdir = freecadcmd("-c", PROBE, home=home)
    assert userdir == str(home / ".local" / "share" / "FreeCAD") + "/"
    assert os.path.realpath(module) == os.path.join(REPO, "clients", "freecad", "wrench_freecad.py")
    assert os.path.realpath(client) == os.path.join(REPO, "clients", "python", "wrenchd.py")
    # linking again is fine; a directory in the way is refused, not overwritten
    make("freecad-link", "HOME=%s" % home)
    link.unlink()
    link.mkdir()
    proc = subprocess.run(["make", "-C", REPO, "--no-print-directory", "freecad-link",
                           "HOME=%s" % home], capture_output=True, timeout=60)
    assert proc.returncode != 0 and b"exists and is no link" in proc.stdout
