# The Wrench workbench: FreeCAD runs this file at start with the GUI (it is
# executed, not imported: FreeCAD, FreeCADGui as Gui and Workbench are
# given).  The commands load when the workbench is first activated.


class WrenchWorkbench(Workbench):  # noqa: F821 (FreeCAD gives Workbench)
    """wrenchd in FreeCAD: where to push a planar part so that it seats in its
    fixture and stays, and where to put the fixels."""

    MenuText = "Wrench"
    ToolTip = ("wrenchd: where to push a planar part so that it seats itself in its fixels "
               "and then holds still (set both), and where to put the fixels")

    def __init__(self):
        import os
        import sys
        for path in sys.path:
            icon = os.path.join(path, "Resources", "icons", "Wrench.svg")
            if os.path.isfile(os.path.join(path, "wrench_freecad.py")) and os.path.isfile(icon):
                self.__class__.Icon = icon
                break

    def Initialize(self):
        import wrench_commands
        self.appendToolbar("Wrench", wrench_commands.TOOLBAR)
        self.appendMenu("&Wrench", wrench_commands.MENU)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(WrenchWorkbench())  # noqa: F821 (FreeCAD gives Gui)
