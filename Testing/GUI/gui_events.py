"""Writes RockDEM's GUI test event files (ParaView's recorded-test XML).

    python3 gui_events.py            # rewrites gui_*.xml beside this file

The event files are what ParaView plays (`paraview --test-script=...`); they are kept in
the repository and are the tests. This script is how they were written: the widget paths
of ParaView 5.11 (menus, the Properties panel, the VCR toolbar, file dialogs) in one place,
so a path that changes with a ParaView release changes once. Python lines run in the GUI's
Python shell and call rockdem_gui.py.
"""
import os
from xml.sax.saxutils import quoteattr

HERE = os.path.dirname(os.path.abspath(__file__))
MAIN = "pqClientMainWindow"
PANEL = MAIN + "/propertiesDock/propertiesPanel"
PROPERTY = PANEL + "/scrollArea/qt_scrollarea_viewport/scrollAreaWidgetContents/PropertiesFrame/ProxyPanel"
CONSOLE = MAIN + "/pythonShellDock/pythonShell/consoleWidget"
VIEWPORT = MAIN + ("/centralwidget/MultiViewWidget/CoreWidget/qt_tabwidget_stackedwidget/"
                   "MultiViewWidget1/Container/Frame.0/CentralWidgetFrame/Viewport")
DOCK = MAIN + "/pqRockDEMTestDock/Body"


def event(obj, command, arguments=""):
    return "  <pqevent object=%s command=%s arguments=%s />" % (quoteattr(obj), quoteattr(command),
                                                               quoteattr(arguments))


def python(code):
    """One line of Python in the GUI's Python shell."""
    return event(CONSOLE, "executeCommand", code)


def check_text(path, text):
    """The text a widget shows (a pqcheck: fails the test when it differs)."""
    return "  <pqcheck object=%s property=\"text\" arguments=%s />" % (quoteattr(path), quoteattr(text))


def compare_view(obj, baseline, width, height, threshold=10):
    return ("  <pqcompareview object=%s baseline=%s width=\"%d\" height=\"%d\" threshold=\"%d\" />"
            % (quoteattr(obj), quoteattr("@BASELINE@/" + baseline), width, height, threshold))


def menu(name, item):
    return [event(MAIN + "/menubar", "activate", name), event(MAIN + "/menubar/" + name + "/Alphabetical", "activate", item)]


def prop(name, widget, value):
    """Types a value into a property's widget: LineEdit0 (int), DoubleLineEdit0 (real),
    DoubleRangeWidget/DoubleLineEdit (real with a slider), DoubleLineEdit2 (third of three)."""
    return event(PROPERTY + "/" + name + "/" + widget, "set_string", value)


def button(name):
    return event(PROPERTY + "/" + name + "/1QPushButton0", "activate")


def combo(name, text):
    return event(PROPERTY + "/" + name + "/ComboBox", "activated", text)


def wait(ms=500):
    return event(MAIN, "process_events", str(ms))


APPLY = event(PANEL + "/Accept", "activate")
PLAY = event(MAIN + "/VCRToolbar/actionVCRPlay", "activate")
SCROLL_PANEL = event(PANEL + "/scrollArea/qt_scrollarea_vcontainer/1QScrollBar0", "set_int", "430")


def open_file(path):
    return [event(MAIN + "/menubar/menu_File", "activate", "actionFileOpen"),
            event(MAIN + "/FileOpenDialog", "filesSelected", path)]


def load_state(path, data_files=False):
    """File > Load State; a state that names data files (a checkpoint, a state file) asks
    how to find them: "Use File Names From State" (OK)."""
    events = [event(MAIN + "/menubar/menu_File", "activate", "actionFileLoadServerState"),
              event(MAIN + "/FileLoadServerStateDialog", "filesSelected", path)]
    if data_files:
        events.append(event("LoadStateOptionsDialog/widget/OKButton", "activate"))
    return events


def save_state(path):
    return [event(MAIN + "/menubar/menu_File", "activate", "actionFileSaveServerState"),
            event(MAIN + "/FileSaveServerStateDialog", "filesSelected", path)]


def write(name, comment, events):
    lines = ['<?xml version="1.0" ?>', "<!-- " + comment.strip() + " -->", "<pqevents>"]
    lines += [python("import rockdem_gui as g"), wait(500)]
    for e in events:
        lines += e if isinstance(e, list) else [e]
    lines += [python("g.finish()"), "</pqevents>"]
    with open(os.path.join(HERE, name), "w") as f:
        f.write("\n".join(lines) + "\n")


# --- 1. the plugin, a pack, Add and Grow --------------------------------------------------
write("gui_pack.xml", """
RockDEM GUI test: load the plugin through Tools > Manage Plugins, build a pack with DEM Pack
Source, press Add Elements and Grow Elements, and see Number Of Elements and Current
Porosity follow in the Properties panel (read-only values, an integer among them); the
particles are drawn at their true size (compared with a baseline picture) and the presses
are recorded in a saved state. Written by gui_events.py.""", [
    python("g.shot('00_empty')"),
    event(MAIN + "/menubar", "activate", "menuTools"),
    event(MAIN + "/menubar/menuTools", "activate", "actionManage_Plugins"),
    event(MAIN + "/PluginManagerDialog/splitter/localGroup/loadLocal", "activate"),
    event(MAIN + "/PluginManagerDialog/pqFileDialog", "filesSelected", "@PLUGIN@"),
    event(MAIN + "/PluginManagerDialog/buttonBox/1QPushButton0", "activate"),
    menu("menuSources", "DEMPackSource"),
    prop("InitialElements", "LineEdit0", "500"),
    prop("XDimension", "DoubleLineEdit0", "0.03"),
    prop("YDimension", "DoubleLineEdit0", "0.03"),
    prop("ZDimension", "DoubleLineEdit0", "0.05"),
    prop("MinimumSize", "DoubleLineEdit0", "0.001"),
    prop("MaximumSize", "DoubleLineEdit0", "0.0015"),
    prop("YoungsModulus", "DoubleLineEdit0", "1e7"),
    APPLY,
    SCROLL_PANEL,
    check_text(PROPERTY + "/NumberOfElements/Value", "500"),
    python("pack = g.source('DEMPackSource1'); d = GetDisplayProperties(pack, GetActiveView()); "
           "g.check(d.Representation == 'DEM Spheres' and d.ColorArrayName[1] == 'Radius', "
           "'the pack is drawn as DEM Spheres coloured by Radius (%s, %s)' % (d.Representation, d.ColorArrayName))"),
    python("g.shot('01_pack_built'); p0 = g.value(pack, 'CurrentPorosity')"),
    button("AddElements"),
    wait(200),
    check_text(PROPERTY + "/NumberOfElements/Value", "1857"),
    check_text(PROPERTY + "/CurrentPorosity/Value", "0.707277"),
    python("p1 = g.value(pack, 'CurrentPorosity'); g.check(g.value(pack, 'NumberOfElements') == 1857 and p1 < p0, "
           "'after Add Elements the panel shows 1857 elements and Current Porosity %.6g (was %.6g), "
           "without re-selecting the source' % (p1, p0))"),
    button("GrowElements"),
    wait(200),
    check_text(PROPERTY + "/CurrentPorosity/Value", "0.638524"),
    python("p2 = g.value(pack, 'CurrentPorosity'); g.check(g.value(pack, 'NumberOfElements') == 1857 and p2 < p1, "
           "'after Grow Elements: Current Porosity %.6g (grown, same 1857 elements)' % p2)"),
    python("g.shot('02_pack_grown')"),
    compare_view(VIEWPORT, "gui_pack_spheres.png", 400, 400),
    save_state("@OUT@/pack.pvsm"),
    python("import os; g.check('value=\"AG\"' in open(os.path.join(g.OUT, 'pack.pvsm')).read(), "
           "'File > Save State recorded the presses in the pack (Commands = AG)')"),
])

# --- 2. from a pack to a DFN: settle, consolidate, cement, compress, export ---------------
write("gui_workflow.xml", """
RockDEM GUI test: the workflow from an empty pipeline to a DFN, as a user does it in the GUI
(Documentation/GUI-Walkthrough.md shows its screenshots). A pack is settled with Play (DEM
Load Test, Number Of Frames 0: until settled; Apply shows the first frame only),
consolidated (Mode Isotropic, until done), cemented, loaded in unconfined compression (Number
Of Frames 0: until the test finishes) with the DEM Test dock showing the curve (compared
with a baseline picture) and exporting it as CSV, and its broken bonds exported as a DFN;
the state is saved through File > Save State. Written by gui_events.py.""", [
    menu("menuSources", "DEMPackSource"),
    prop("InitialElements", "LineEdit0", "400"),
    prop("XDimension", "DoubleLineEdit0", "0.02"),
    prop("YDimension", "DoubleLineEdit0", "0.02"),
    prop("ZDimension", "DoubleLineEdit0", "0.03"),
    prop("MinimumSize", "DoubleLineEdit0", "0.001"),
    prop("MaximumSize", "DoubleLineEdit0", "0.0015"),
    prop("YoungsModulus", "DoubleLineEdit0", "1e7"),
    APPLY,
    button("GrowElements"),
    wait(300),
    # settle under gravity: Number Of Frames 0, until settled
    menu("menuFilters", "DEMLoadTest"),
    prop("FrameInterval", "DoubleLineEdit0", "0.005"),
    APPLY,
    wait(300),
    python("settle = g.source('DEMLoadTest1'); scene = GetAnimationScene(); "
           "g.check(scene.AnimationTime == 0.0 and g.value(settle, 'ModelTime') == 0.0 and g.value(settle, 'FrameSteps') == 563, "
           "'Apply shows the first frame and computes nothing ahead (time %g, Model Time %g s, frames of %d steps)' "
           "% (scene.AnimationTime, g.value(settle, 'ModelTime'), g.value(settle, 'FrameSteps')))"),
    python("g.check(scene.PlayMode == 'Snap To TimeSteps' and len(settle.TimestepValues) > 1, "
           "'the animation follows the stage frames (%s, %d frames published)' % (scene.PlayMode, len(settle.TimestepValues)))"),
    python("g.shot('03_settle_applied')"),
    PLAY,
    wait(500),
    python("g.check(g.value(settle, 'Finished') == 1 and 'settled' in g.value(settle, 'Status') "
           "and abs(scene.AnimationTime - settle.TimestepValues[-1]) < 1e-12, "
           "'Play ran frame by frame until the pack settled and stopped there (t = %.4g s, %s)' "
           "% (scene.AnimationTime, g.value(settle, 'Status')[:60]))"),
    python("g.check(g.value(settle, 'CurrentPorosity') < 0.6 and g.value(settle, 'NumberOfContacts') > 500, "
           "'the panel values followed the frames: porosity %.4g, %d contacts' "
           "% (g.value(settle, 'CurrentPorosity'), g.value(settle, 'NumberOfContacts')))"),
    python("g.shot('04_settled')"),
    # consolidate: Mode Isotropic, until done
    menu("menuFilters", "DEMLoadTest"),
    combo("Mode", "Isotropic"),
    prop("ConfiningStress", "DoubleLineEdit0", "2e4"),
    prop("Gravity", "DoubleLineEdit2", "0"),
    prop("FrameInterval", "DoubleLineEdit0", "0.002"),
    APPLY,
    PLAY,
    wait(500),
    python("iso = g.source('DEMLoadTest2'); g.check(g.value(iso, 'Stage') == 'done' and g.value(iso, 'Finished') == 1, "
           "'the isotropic consolidation ran until done (%s)' % g.value(iso, 'Status')[:50])"),
    python("g.shot('05_consolidated')"),
    # cement
    menu("menuFilters", "DEMCement"),
    prop("GapTolerance", "DoubleRangeWidget/DoubleLineEdit", "0.1"),
    prop("BondModulus", "DoubleLineEdit0", "2e7"),
    prop("TensileStrength", "DoubleLineEdit0", "2e5"),
    prop("Cohesion", "DoubleLineEdit0", "4e5"),
    prop("StrengthScatter", "DoubleRangeWidget/DoubleLineEdit", "0.2"),
    APPLY,
    wait(300),
    python("cement = g.source('DEMCement1'); g.check(g.value(cement, 'Bonds') > 1000, "
           "'DEM Cement installed %d bonds (read-only Bonds, an integer, shown)' % g.value(cement, 'Bonds'))"),
    python("dc = GetDisplayProperties(cement); v = GetActiveView(); "
           "g.check(dc.ColorArrayName[1] == 'Radius' and GetScalarBar(GetColorTransferFunction('Radius'), v).Visibility == 1 "
           "and GetScalarBar(GetColorTransferFunction('Displacement'), v).Visibility == 0, "
           "'the cemented model is coloured by Radius with its legend, not by the Displacement of the stage before (%s)' "
           "% (dc.ColorArrayName,))"),
    python("g.shot('06_cemented')"),
    # unconfined compression until the test finishes
    menu("menuFilters", "DEMLoadTest"),
    combo("Mode", "Compression"),
    prop("Gravity", "DoubleLineEdit2", "0"),
    prop("StrainRate", "DoubleLineEdit0", "2"),
    prop("MaxStrain", "DoubleRangeWidget/DoubleLineEdit", "0.04"),
    prop("FrameInterval", "DoubleLineEdit0", "0.00025"),
    APPLY,
    wait(1000),
    python("press = g.source('DEMLoadTest3'); g.check(scene.AnimationTime == 0.0 and g.value(press, 'Stage') == 'shear' "
           "and g.value(press, 'EstimatedSteps') > 0 and g.value(press, 'EstimatedRunTime') > 0, "
           "'the compression says how long it is before it runs: %.4g steps, about %.3g s' "
           "% (g.value(press, 'EstimatedSteps'), g.value(press, 'EstimatedRunTime')))"),
    python("g.check(GetDisplayProperties(press).ColorArrayName[1] == 'Displacement', "
           "'the load test is coloured by Displacement')"),
    python("g.shot('07_compression_applied')"),
    PLAY,
    wait(1000),
    python("g.check(g.value(press, 'Finished') == 1 and g.value(press, 'Stage') == 'done' "
           "and abs(scene.AnimationTime - press.TimestepValues[-1]) < 1e-12, "
           "'Play ran the test to its end (Max Strain reached) and stopped there: t = %.4g s, axial strain %.4g' "
           "% (scene.AnimationTime, g.value(press, 'AxialStrain')))"),
    python("g.check(g.value(press, 'PeakStress') > 5e4 and g.value(press, 'BrokenBonds') > 20, "
           "'Peak Stress %.4g Pa, %d broken bonds' % (g.value(press, 'PeakStress'), g.value(press, 'BrokenBonds')))"),
    check_text(DOCK + "/Stage", "done"),
    python("g.shot('08_compression_done')"),
    compare_view(DOCK + "/Chart", "dem_test_chart.png", 400, 300),
    event(DOCK + "/ExportCSV", "activate"),
    event(MAIN + "/ExportHistoryDialog", "filesSelected", "@OUT@/exported_history.csv"),
    python("import csv, os; rows = list(csv.reader(open(os.path.join(g.OUT, 'exported_history.csv')))); "
           "g.check(rows[0][0] == 'Time (s)' and len(rows) > 10, "
           "'Export CSV wrote the history: %d rows, columns %s ...' % (len(rows) - 1, rows[0][:3]))"),
    # the fractures
    menu("menuFilters", "DEMFracturesToDFN"),
    APPLY,
    wait(1000),
    python("dfn = g.source('DEMFracturesToDFN1'); g.check(g.value(dfn, 'BrokenBonds') == g.value(press, 'BrokenBonds') "
           "and g.value(dfn, 'DiscsEmitted') >= 1, 'DEM Fractures To DFN read the %d broken bonds of the test: %s' "
           "% (g.value(dfn, 'BrokenBonds'), g.value(dfn, 'LastMessage').splitlines()[0]))"),
    python("rv = [v for v in GetViews() if v.GetXMLName() == 'RenderView'][0]; lut = GetColorTransferFunction('Set'); "
           "g.check(GetDisplayProperties(dfn, rv).ColorArrayName[1] == 'Set' and lut.InterpretValuesAsCategories == 1, "
           "'the discs are coloured by Set with a categorical legend (%s)' % list(lut.Annotations))"),
    python("s = Show(press, rv); s.Opacity = 0.25; Render(rv)"),
    wait(300),
    python("g.shot('09_dfn')"),
    save_state("@OUT@/workflow.pvsm"),
    python("import os; g.check(os.path.exists(os.path.join(g.OUT, 'workflow.pvsm')), 'File > Save State wrote workflow.pvsm')"),
])

# --- 3. File > Open of a .rdem ---------------------------------------------------------
write("gui_open_state_file.xml", """
RockDEM GUI test: File > Open of a RockDEM state file (.rdem, the main job's tested specimen
from the smoke run) makes a DEM State Reader; Apply shows the specimen as true-size spheres
coloured by Radius (not by a cell array of the bonds), with its read-only counts (integers)
in the panel. Written by gui_events.py.""", [
    open_file("@DATA@/specimen.rdem"),
    APPLY,
    wait(500),
    python("r = GetActiveSource(); g.check(r.GetXMLName() == 'DEMStateReader', 'File > Open made a %s' % r.GetXMLName())"),
    python("n = g.value(r, 'NumberOfParticles'); b = g.value(r, 'Bonds'); "
           "import csv; g.check(n == int(next(csv.DictReader(open(g.DATA + '/results.csv')))['elements']) and b > 0, "
           "'the reader shows %d particles (as the main job) and %d bonds' % (n, b))"),
    check_text(PROPERTY + "/Stage/Value", "done"),
    python("d = GetDisplayProperties(r); g.check(d.Representation == 'DEM Spheres' and d.ColorArrayName[1] == 'Radius', "
           "'the specimen is drawn as DEM Spheres coloured by Radius (%s, %s)' % (d.Representation, d.ColorArrayName))"),
    python("g.shot('10_opened_rdem')"),
])

# --- 4. Load State of a state saved from the GUI ----------------------------------------
write("gui_load_state.xml", """
RockDEM GUI test: File > Load State of the state saved by the pack test (gui_pack.xml) rebuilds
the same pack: the Add and Grow presses are recorded in it, so Number Of Elements and Current
Porosity are those of the saved pack. Written by gui_events.py.""", [
    load_state("@DATA@/pack.pvsm"),
    wait(500),
    python("SetActiveSource(g.source('DEMPackSource1'))"),
    wait(300),
    python("pack = g.source('DEMPackSource1'); g.check(g.value(pack, 'NumberOfElements') == 1857 and "
           "abs(g.value(pack, 'CurrentPorosity') - 0.638524) < 5e-7, 'Load State rebuilt the pack with its Add and Grow: "
           "%d elements, porosity %.6g' % (g.value(pack, 'NumberOfElements'), g.value(pack, 'CurrentPorosity')))"),
    SCROLL_PANEL,
    check_text(PROPERTY + "/NumberOfElements/Value", "1857"),
    python("g.shot('11_state_loaded')"),
])

# --- 5. Load State of the main job's state -----------------------------------------------
write("gui_main_job_state.xml", """
RockDEM GUI test: File > Load State of the main job's main_job.pvsm (the smoke run's) reopens
the whole pipeline in its layout (the 3D view beside the test chart) at the end of the test,
every stepping stage taking its frames from its checkpoint (.rdem) instead of computing them:
the same particle and bond counts, the tested specimen shown, within 30 s. Written by
gui_events.py.""", [
    python("g.start_clock()"),
    load_state("@DATA@/main_job.pvsm", data_files=True),
    wait(500),
    python("g.note('reopened in %.1f s' % g.seconds()); seconds = g.seconds()"),
    python("tests = [p for (n, i), p in GetSources().items() if p.GetXMLName() == 'DEMLoadTest']; "
           "press = [t for t in tests if t.Mode == 'Compression'][0]; import csv; row = next(csv.DictReader(open(g.DATA + '/results.csv'))); "
           "g.check(g.value(press, 'Bonds') == int(row['bonds']) and g.value(press, 'Stage') == 'done', "
           "'the compression is back at its end (Stage done) with the %d bonds of the main job' % g.value(press, 'Bonds'))"),
    python("info = press.GetDataInformation(); g.check(info.GetNumberOfPoints() >= int(row['elements']) and "
           "GetDisplayProperties(press, GetActiveView()).Visibility == 1, "
           "'the tested specimen is shown: %d particles' % int(row['elements']))"),
    python("views = GetViews(); g.check(len(GetLayouts()) >= 1 and len(views) >= 2, "
           "'the layout is back: %d layout(s), %d views (%s)' % (len(GetLayouts()), len(views), [v.GetXMLName() for v in views]))"),
    python("g.check(seconds < 30.0, 'reopened in %.1f s (under 30 s): the frames came from the checkpoints' % seconds)"),
    python("g.shot('12_main_job_state')"),
    # The main job's state holds the test chart's row selection: an Apply after loading it
    # (the sequence that crashed ParaView with the old selection) keeps ParaView running.
    menu("menuSources", "SphereSource"),
    APPLY,
    wait(500),
    python("g.check(g.source('Sphere1') is not None and any(p.GetXMLName() == 'AppendSelections' for p in GetSources().values()), "
           "'a Sphere applied after loading the main job state (with its row selection): ParaView is still running')"),
])

# --- 6. The sequence that used to crash ParaView ----------------------------------------
write("gui_old_crash.xml", """
RockDEM GUI test: the sequence that crashed ParaView 5.11 (SIGSEGV in
pqSelectionInputWidget::preAccept): rockdem.show_test_chart in the Python shell (it selects
the shear rows of the test history), then an Apply of something else (a Sphere, and File >
Open of a .rdem). The selection is now built the way the GUI builds one, and ParaView keeps
running. Written by gui_events.py.""", [
    python("import rockdem; p = DEMPackSource(InitialElements=300, XDimension=0.02, YDimension=0.02, ZDimension=0.02, "
           "MinimumSize=0.001, MaximumSize=0.0015, YoungsModulus=1e7); "
           "t = DEMLoadTest(Input=p, Mode='Compression', Gravity=[0, 0, 0], StrainRate=2.0, MaxStrain=0.005, FrameInterval=0.0005)"),
    python("t.UpdatePipeline(rockdem.END_OF_RUN); chart = rockdem.show_test_chart(t)"),
    python("g.check(any(s.GetXMLName() == 'AppendSelections' for s in GetSources().values()), "
           "'show_test_chart made its row selection through an AppendSelections')"),
    menu("menuSources", "SphereSource"),
    APPLY,
    wait(500),
    open_file("@DATA@/specimen.rdem"),
    APPLY,
    wait(500),
    python("g.check(g.source('Sphere1') is not None and GetActiveSource().GetXMLName() == 'DEMStateReader', "
           "'Apply after show_test_chart: a Sphere and a .rdem were applied, ParaView is still running')"),
])

# --- 7. A calibration from the GUI's Python shell ----------------------------------------
write("gui_calibration.xml", """
RockDEM GUI test: a calibration run from the ParaView GUI the way Documentation/Calibration.md
tells a user to (View > Python Shell, import rockdem), with its progress printed in the shell:
a 300-grain specimen calibrated to E = 500 MPa and UCS = 1 MPa, then its parameter file
rebuilt as a pipeline (rockdem.build_specimen: DEM Pack Source -> DEM Cement) and loaded in
unconfined compression through the Filters menu and Apply, as a user continues from it.
Written by gui_events.py.""", [
    python("import rockdem, json; recs = []; folder = g.OUT + '/calibration'; before = len(GetSources())"),
    python("res = rockdem.calibrate({'name': 'GUI rock', 'youngs_modulus': 5e8, 'ucs': 1e6}, "
           "{'elements': 300, 'seed': 3, 'max_tests': 12}, "
           "progress=lambda r: (recs.append(r), print('test %d (%s): errors %s' % (r['test'], r['stage'], r['errors']))), "
           "output=folder)"),
    python("g.check(res['converged'] and all(abs(e) <= 0.05 for e in res['errors'].values()), "
           "'the calibration converged in the GUI: %d specimen tests, %.1f s, errors %s' "
           "% (res['tests'], res['seconds'], res['errors']))"),
    python("g.check(len(recs) == len(res['iterations']) >= 2 and len(GetSources()) == before, "
           "'one progress record per test (%d), and the calibration left no proxy behind (%d sources)' "
           "% (len(recs), len(GetSources())))"),
    python("pack, cement = rockdem.build_specimen(folder + '/parameters.json'); SetActiveSource(cement); "
           "Show(cement); Render(); doc = rockdem.load_parameters(folder + '/parameters.json')"),
    python("g.check(all(abs(cement.GetPropertyValue(k) - v) <= 1e-12 * abs(v) for k, v in doc['cement'].items() "
           "if k != 'RandomSeed') and g.value(cement, 'Bonds') > 0, "
           "'build_specimen made the calibrated DEM Cement in the pipeline: Bond Modulus %.4g Pa, Tensile %.4g Pa, "
           "%d bonds' % (cement.BondModulus, cement.TensileStrength, g.value(cement, 'Bonds')))"),
    menu("menuFilters", "DEMLoadTest"),
    combo("Mode", "Compression"),
    APPLY,
    wait(1000),
    python("t = GetActiveSource(); g.check(t.GetXMLName() == 'DEMLoadTest' and t.Input.SMProxy == cement.SMProxy "
           "and g.value(t, 'Bonds') == g.value(cement, 'Bonds') and g.value(t, 'SuggestedStrainRate') > 0, "
           "'DEM Load Test applied from the Filters menu on the calibrated specimen: its %d bonds, Suggested Strain "
           "Rate %.4g 1/s' % (g.value(t, 'Bonds'), g.value(t, 'SuggestedStrainRate')))"),
    python("g.shot('calibrated_specimen')"),
])
