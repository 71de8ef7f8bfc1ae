"""D44's peer: the disk crossing the steel bridge in Exudyn, a multibody code, written from
its documented items (pip install exudyn numpy).

The bridge is Exudyn's ANCF Cable2D (Euler-Bernoulli with axial stretch: it leaves out the
shear, which softens D44's bridge by 0.7 %), pinned at x = 0 and on a roller at x = L,
without self-weight.
The disk is a rigid body in the plane on a penalty contact with friction, its
ContactFrictionCircleCable2D: stiff enough that the disk sinks 10 micrometres under its
weight, damped at a twentieth of critical (of 0, 0.01, 0.025, 0.05, 0.1 and 1 of critical, where
its force spikes least as the circle passes from one segment to the next), the friction as
stiff. Exudyn's
generalized-alpha integrator takes a fixed step.

Usage: python benches/d44_peer.py OUT.csv STEPS [HISTORY.csv]
writes t, the disk's x, the midspan's deflection w and acceleration a, and the contact force
along y, R_y = m (ÿ + g), every output interval (0.005 s) over D44's 3 s, and prints the
wall time of the solve alone. Given rollbeam's history.csv of D44 (converged: every default
but `solver: {accuracy: 1e-4}`), it prints how far its w, a and R_y lie from rollbeam's at
each output time, over the largest of each.
"""

import sys
import time

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    Cable2D,
    CoordinateConstraint,
    Force,
    MarkerBodyCable2DShape,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    NodeGenericData,
    NodePointGround,
    NodeRigidBody2D,
    ObjectContactFrictionCircleCable2D,
    ObjectRigidBody2D,
    Point2DS1,
    SensorBody,
    SensorNode,
)

# D44 (STUDIES.md section 4): HEB 360 steel, L = 20 m; a 1500 kg disk of radius 0.4 m at
# 17.6 m/s rolling (omega0 = -44 1/s) from the left support, over 3 s.
LENGTH, E, RHO, AREA, INERTIA = 20.0, 210.0e9, 7850.0, 181.0e-4, 43190.0e-8
MASS, RADIUS, SPEED, OMEGA0, G = 1500.0, 0.4, 17.6, -44.0, 9.81
DURATION, INTERVAL = 3.0, 0.005
SINK = 1.0e-5
SEGMENTS = 8
ELEMENTS = 40


def build(elements):
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    fixed = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    h = LENGTH / elements
    nodes = [
        mbs.AddNode(Point2DS1(referenceCoordinates=[i * h, 0, 1, 0]))
        for i in range(elements + 1)
    ]
    cables = [
        mbs.AddObject(
            Cable2D(
                length=h,
                massPerLength=RHO * AREA,
                bendingStiffness=E * INERTIA,
                axialStiffness=E * AREA,
                nodeNumbers=[nodes[i], nodes[i + 1]],
            )
        )
        for i in range(elements)
    ]
    for node, coordinate in [(nodes[0], 0), (nodes[0], 1), (nodes[-1], 1)]:
        m = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=coordinate))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[fixed, m]))

    disk_node = mbs.AddNode(
        NodeRigidBody2D(
            referenceCoordinates=[0, RADIUS, 0],
            initialVelocities=[SPEED, 0, OMEGA0],
        )
    )
    disk = mbs.AddObject(
        ObjectRigidBody2D(
            nodeNumber=disk_node, mass=MASS, inertia=0.5 * MASS * RADIUS**2
        )
    )
    centre = mbs.AddMarker(MarkerBodyRigid(bodyNumber=disk, localPosition=[0, 0, 0]))
    mbs.AddLoad(Force(markerNumber=centre, loadVector=[0, -MASS * G, 0]))

    # The weight shared by about two segments in contact, each sinking SINK.
    stiffness = MASS * G / (2 * SINK)
    damping = 0.1 * np.sqrt(stiffness * MASS)
    for cable in cables:
        shape = mbs.AddMarker(MarkerBodyCable2DShape(bodyNumber=cable, numberOfSegments=SEGMENTS))
        data = mbs.AddNode(
            NodeGenericData(
                initialCoordinates=[0.1] * SEGMENTS + [-2] * SEGMENTS + [0.0] * SEGMENTS,
                numberOfDataCoordinates=3 * SEGMENTS,
            )
        )
        mbs.AddObject(
            ObjectContactFrictionCircleCable2D(
                markerNumbers=[centre, shape],
                nodeNumber=data,
                numberOfContactSegments=SEGMENTS,
                contactStiffness=stiffness,
                contactDamping=damping,
                frictionStiffness=stiffness,
                frictionVelocityPenalty=damping,
                frictionCoefficient=1.0,
                circleRadius=RADIUS,
            )
        )

    mid = nodes[elements // 2]
    sensors = [
        mbs.AddSensor(SensorBody(bodyNumber=disk, storeInternal=True, outputVariableType=exu.OutputVariableType.Position)),
        mbs.AddSensor(SensorBody(bodyNumber=disk, storeInternal=True, outputVariableType=exu.OutputVariableType.Acceleration)),
        mbs.AddSensor(SensorNode(nodeNumber=mid, storeInternal=True, outputVariableType=exu.OutputVariableType.Displacement)),
        mbs.AddSensor(SensorNode(nodeNumber=mid, storeInternal=True, outputVariableType=exu.OutputVariableType.Acceleration)),
    ]
    mbs.Assemble()
    return sc, mbs, sensors


def solve(steps, elements):
    sc, mbs, sensors = build(elements)
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime = DURATION
    settings.timeIntegration.numberOfSteps = steps
    settings.timeIntegration.verboseMode = 0
    settings.timeIntegration.newton.useModifiedNewton = True
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = INTERVAL
    start = time.perf_counter()
    exu.SolveDynamic(mbs, settings)
    wall = time.perf_counter() - start
    position, acceleration, w, a = (mbs.GetSensorStoredData(s) for s in sensors)
    rows = np.column_stack(
        [position[:, 0], position[:, 1], w[:, 2], a[:, 2], MASS * (acceleration[:, 2] + G)]
    )
    return rows, wall


def deviations(rows, history):
    """Each of w, a and R_y: the largest distance from rollbeam's at its output times while
    the disk is on the beam (R_y) or over the run, over rollbeam's largest."""
    with open(history) as f:
        names = f.readline().strip().split(",")
    theirs = np.genfromtxt(history, delimiter=",", skip_header=1, filling_values=np.nan)
    column = {name: theirs[:, i] for i, name in enumerate(names)}
    _, first = np.unique(rows[:, 0].round(9), return_index=True)
    rows = rows[first]
    t = column["t"]
    out = {}
    for name, ours in [("mid.w", rows[:, 2]), ("mid.a", rows[:, 3]), ("disk.rn", rows[:, 4])]:
        reference = column[name]
        on = ~np.isnan(reference)
        off = np.abs(np.interp(t[on], rows[:, 0], ours) - reference[on])
        out[name] = off.max() / np.abs(reference[on]).max()
    return out


def main():
    out, steps = sys.argv[1], int(sys.argv[2])
    rows, wall = solve(steps, ELEMENTS)
    np.savetxt(out, rows, delimiter=",", header="t,disk.x,mid.w,mid.a,disk.ry", comments="")
    print(f"steps {steps} wall_s {wall:.3f}")
    if len(sys.argv) > 3:
        for name, off in deviations(rows, sys.argv[3]).items():
            print(f"{name} off rollbeam's by {off:.2e} of its largest")


if __name__ == "__main__":
    main()
