# The Wrench workbench (wrenchd in FreeCAD): what FreeCAD runs at start,
# with or without the GUI.  Nothing is needed without the GUI: the objects'
# module, wrench_freecad, is imported when a document holding them is
# opened, and scripts import it themselves (freecadcmd finds it on this
# directory's path).  InitGui.py adds the workbench.
