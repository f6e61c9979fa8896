"""Saving and reopening a RockDEM pipeline (Documentation/StateFile.md).

Parent process: a triaxial test (checkpointed mid-shear) (DEM Pack Source -> DEM Load Test) runs N frames with a
Checkpoint File; the pipeline is saved as a ParaView state (.pvsm); an uninterrupted run of
2N frames is the reference. Then, in NEW pvpython processes:
  1. LoadState(recipe.pvsm) rebuilds the pipeline; recomputed to frame N it is bitwise the
     run that was saved (the .pvsm is the recipe: parameters, not data).
     DEM State Reader (the checkpoint) -> DEM Load Test (same settings, N frames) continues
     the run; that pipeline is saved as continue.pvsm.
  2. LoadState(continue.pvsm) rebuilds reader -> load test and continues again.
Both continued runs end bitwise identical to the uninterrupted 2N-frame run (positions,
velocities, angular velocities, forces, contact history, walls and test history).
The state file is also written with SaveData (DEM State Writer) and read back.
"""
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from paraview import servermanager
from paraview.simple import Delete, FindSource, LoadState, SaveData, SaveState

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

N = 8
DT = 0.001  # s, Frame Interval: frame N is in the shearing stage, past consolidation
TRIAXIAL = dict(Mode='Triaxial', ConfiningStress=1.0e5, StrainRate=0.5, SampleInterval=100,
                Gravity=[0.0, 0.0, 0.0], FrameInterval=DT)


def arrays_of(proxy):
    """Every per-particle, contact, wall and test array of the model, as numpy arrays."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    data = servermanager.Fetch(proxy)
    out = {}
    for b in range(data.GetNumberOfBlocks()):
        name = data.GetMetaData(b).Get(data.NAME())
        block = data.GetBlock(b)
        if name == 'Particles':
            out['Points'] = vtk_to_numpy(block.GetPoints().GetData()).copy()
            pd = block.GetPointData()
            for a in ('Id', 'Velocity', 'AngularVelocity', 'Displacement', 'Force', 'Torque'):
                out[a] = vtk_to_numpy(pd.GetArray(a)).copy()
        elif name == 'Contacts':
            fd = block.GetFieldData()
            for a in ('IdA', 'IdB', 'ShearSpring'):
                out['Contacts' + a] = vtk_to_numpy(fd.GetArray(a)).copy()
    fd = data.GetFieldData()
    for a in ('WallState', 'TestState', 'TestHistory', 'Time', 'Step'):
        out[a] = vtk_to_numpy(fd.GetArray(a)).copy()
    return out


def save_arrays(path, arrays):
    np.savez(path, **arrays)


def load_arrays(path):
    with np.load(path) as z:
        return {k: z[k] for k in z.files}


def first_difference(a, b):
    """'' when every array is bitwise identical, else the first differing name."""
    if sorted(a) != sorted(b):
        return 'array names %s vs %s' % (sorted(a), sorted(b))
    for k in sorted(a):
        x, y = a[k], b[k]
        if x.shape != y.shape or x.dtype != y.dtype:
            return '%s (shape %s vs %s)' % (k, x.shape, y.shape)
        if x.tobytes() != y.tobytes():
            return k
    return ''


def continue_from(checkpoint):
    """DEM State Reader -> DEM Load Test with the run's settings, N more frames."""
    # DEMStateReader and DEMLoadTest are put in this module's namespace by load_rockdem.
    r = DEMStateReader(registrationName='Checkpoint', FileName=checkpoint)
    lt = DEMLoadTest(registrationName='Continued', Input=r, NumberOfFrames=N, **TRIAXIAL)
    lt.UpdatePipeline(N * DT)
    return r, lt


def child_one(work):
    checks = Checks()
    load_rockdem(globals())
    LoadState(os.path.join(work, 'recipe.pvsm'))
    test = FindSource('Test')
    checks.check(test is not None, 'LoadState rebuilt the pipeline (the DEM Load Test is there)')
    test.UpdatePipeline(N * DT)
    rebuilt = arrays_of(test)
    diff = first_difference(rebuilt, load_arrays(os.path.join(work, 'saved_at_N.npz')))
    checks.check(diff == '', 'the rebuilt pipeline recomputes frame N bitwise (%s)' % (diff or 'identical'))
    r, lt = continue_from(os.path.join(work, 'checkpoint.rdem'))
    r.UpdatePropertyInformation()
    checks.check(r.GetPropertyValue('Stage') == 'shear',
                 'the checkpoint holds a triaxial test mid-shear (stage %s)' % r.GetPropertyValue('Stage'))
    save_arrays(os.path.join(work, 'continued_1.npz'), arrays_of(lt))
    SaveState(os.path.join(work, 'continue.pvsm'))
    checks.finish()


def child_two(work):
    checks = Checks()
    load_rockdem(globals())
    LoadState(os.path.join(work, 'continue.pvsm'))
    lt = FindSource('Continued')
    checks.check(lt is not None, 'LoadState rebuilt DEM State Reader -> DEM Load Test')
    lt.UpdatePipeline(N * DT)
    save_arrays(os.path.join(work, 'continued_2.npz'), arrays_of(lt))
    checks.finish()


def parent():
    checks = Checks()
    load_rockdem(globals())
    work = tempfile.mkdtemp(prefix='rockdem-state-py-')
    pvpython = os.environ.get('PVPYTHON', 'pvpython')
    pack = DEMPackSource(registrationName='Pack', XDimension=0.02, YDimension=0.02, ZDimension=0.02,
                         InitialElements=500, MinimumSize=0.001, MaximumSize=0.0015,
                         YoungsModulus=1.0e8, RandomSeed=4)
    checkpoint = os.path.join(work, 'checkpoint.rdem')
    test = DEMLoadTest(registrationName='Test', Input=pack, NumberOfFrames=N,
                       CheckpointFile=checkpoint, **TRIAXIAL)
    test.UpdatePipeline(N * DT)
    checks.check(os.path.exists(checkpoint), 'the load test wrote its checkpoint at the last frame')
    checks.check(os.path.exists(os.path.join(work, 'checkpoint.history.csv')),
                 'the test history is beside it as CSV')
    saved = arrays_of(test)
    save_arrays(os.path.join(work, 'saved_at_N.npz'), saved)
    SaveState(os.path.join(work, 'recipe.pvsm'))

    # The same state through File > Save Data (DEM State Writer), read back.
    written = os.path.join(work, 'saved.rdem')
    SaveData(written, proxy=test)
    back = DEMStateReader(FileName=written)
    back.UpdatePipeline()
    diff = first_difference(arrays_of(back), saved)
    checks.check(diff == '', 'SaveData(.rdem) -> DEM State Reader gives the model back (%s)' % (diff or 'identical'))
    checks.check(sorted(f for f in os.listdir(work) if 'tmp' in f) == [], 'no temporary file is left')
    Delete(back)

    # The uninterrupted reference: one load test for 2N frames.
    reference = DEMLoadTest(registrationName='Reference', Input=pack, NumberOfFrames=2 * N, **TRIAXIAL)
    reference.UpdatePipeline(2 * N * DT)
    expected = arrays_of(reference)
    checks.check(expected['Step'][0] > saved['Step'][0], 'the reference ran past the checkpoint')

    env = dict(os.environ)
    for which in ('--child-one', '--child-two'):
        run = subprocess.run([pvpython, os.path.abspath(__file__), which, work], env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        lines = [l for l in run.stdout.splitlines() if l.startswith(('ok', 'FAIL', 'Traceback')) or 'Error' in l]
        print('\n'.join('  [%s] %s' % (which, l) for l in lines))
        checks.check(run.returncode == 0, 'new pvpython process %s succeeded' % which)
        if run.returncode != 0:
            print(run.stdout[-3000:])
    for name, what in (('continued_1.npz', 'reader -> load test in a new process'),
                       ('continued_2.npz', 'the reloaded continue.pvsm')):
        path = os.path.join(work, name)
        if not os.path.exists(path):
            checks.check(False, what + ': no result')
            continue
        got = load_arrays(path)
        diff = first_difference(got, expected)
        checks.check(diff == '', what + ' ends bitwise where the uninterrupted run does (%s)' % (diff or 'identical'))
    if not checks.failed:
        shutil.rmtree(work)
    checks.finish()


if __name__ == '__main__':
    if len(sys.argv) == 3 and sys.argv[1] == '--child-one':
        child_one(sys.argv[2])
    elif len(sys.argv) == 3 and sys.argv[1] == '--child-two':
        child_two(sys.argv[2])
    else:
        parent()
