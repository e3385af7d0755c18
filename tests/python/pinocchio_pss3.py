"""The 3-PSS robot built independently in Pinocchio, from the plant FMU's parameters.

Used by test_pinocchio.py (and described in docs/pinocchio.md). Nothing here calls the
robot library or the FMUs: the mechanism is the tree

    world -- spherical joint at P --------------------------- platform
    world -- prismatic joint along u_i at h_i -- slider i -- universal joint at M_i -- leg i

(12 degrees of freedom: the platform's 3, a slider's 1, a leg's 2, three times) with
three 3D loop closures, the end of leg i (a from M_i along the leg) on the platform's
joint b_i. Pinocchio computes the mass matrix, the bias forces, gravity, the energies
and the constrained accelerations (pin.constraintDynamics, and by hand as a KKT system
with the closure Jacobians and their classical-acceleration drift). A leg's axial
inertia is zero: the universal joint then gives it exactly the kinetic energy of an
S-S leg without spin, I_t |n_dot|^2 / 2 (docs/3pss-dynamics.md, "Leg spin").

The plant's coordinates are mapped in and out here only: Euler angles theta with
R = Rz(thz) Ry(thy) Rx(thx) are Pinocchio's roll-pitch-yaw (pin.rpy), omega in {A} is
R times the spherical joint's velocity (the angular velocity in the platform frame).
"""

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from fmpy import read_model_description

# The FMU names of the model's parameters (those of docs/3pss-model.md and
# docs/fmus.md); the platform inertia is about P in {B}.
GEOMETRY = ["lp", "ld", "gamma", "lb", "alpha", "beta", "a", "strokeMin", "strokeMax"]
INERTIA = ["platformMass", "legMass", "legComFraction", "legTransverseInertia",
           "sliderMass", "g"]
LOADS = ["sliderFriction", "pivotFriction", "endStopStiffness", "endStopDamping"]
TENSOR = ["platformInertia[1,1]", "platformInertia[2,2]", "platformInertia[3,3]",
          "platformInertia[1,2]", "platformInertia[1,3]", "platformInertia[2,3]"]
COM = ["platformCom[1]", "platformCom[2]", "platformCom[3]"]
PARAMETERS = GEOMETRY + INERTIA + LOADS + TENSOR + COM
INPUTS = ["actuatorForce", "torqueCommand", "generalizedForceCommand", "disturbanceTorque"]

# Fixed azimuths (docs/3pss-model.md, "Mechanism and frames").
SLIDER_AZIMUTH = np.radians([-120.0, 0.0, 120.0])    # k_i of h_i
PLATFORM_AZIMUTH = np.radians([0.0, 120.0, -120.0])  # m_i of b_i
ACTUATOR_AZIMUTH = np.radians([0.0, 120.0, -120.0])  # direction of u_i


def start_values(fmu, names=PARAMETERS):
    """The start values of `names` in the FMU's modelDescription (so a changed default
    flows through to the comparison)."""
    variables = {v.name: v for v in read_model_description(fmu).modelVariables}
    return {name: float(variables[name].start) for name in names}


def inertia_about_p(mass, com, inertia_about_com):
    """Parallel axis theorem: an inertia tensor about the centre of mass moved to P."""
    c = np.asarray(com, float)
    return np.asarray(inertia_about_com, float) + mass * (c @ c * np.eye(3) - np.outer(c, c))


def tensor(p):
    """The platform's inertia about P in {B} from the six FMU parameters."""
    xx, yy, zz, xy, xz, yz = (p[n] for n in TENSOR)
    return np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])


def stop_force(p, l, l_dot):
    """The plant's end stop as documented (docs/3pss-dynamics.md, "End stops"): beyond
    the stroke a spring-damper on the slider that pushes towards the stroke and never
    pulls; returns (force along u, spring energy)."""
    k, c = p["endStopStiffness"], p["endStopDamping"]
    low, high = p["strokeMin"], p["strokeMax"]
    if l > high:
        d = l - high
        return min(0.0, -k * d - c * l_dot), 0.5 * k * d * d
    if l < low:
        d = low - l
        return max(0.0, k * d - c * l_dot), 0.5 * k * d * d
    return 0.0, 0.0


@dataclass
class Point:
    """One evaluation of the Pinocchio model at a plant state (theta, omega)."""
    q: np.ndarray
    v: np.ndarray
    R: np.ndarray
    E: np.ndarray        # omega = E thetaDot (pin.rpy, WORLD)
    l: np.ndarray        # slider coordinates
    l_dot: np.ndarray
    J: np.ndarray        # actuator Jacobian, l_dot = J omega
    G: np.ndarray        # v = G omega: the admissible velocities (12 x 3)
    Jc: np.ndarray       # closure Jacobian (9 x 12), Jc v = 0
    drift: np.ndarray    # closure acceleration at zero joint acceleration


class Pss3Pinocchio:
    """The mechanism in Pinocchio for the FMU parameter values `p` (a dict of
    PARAMETERS, e.g. start_values(fmu)). `slider_mass_factors` scales each slider's
    mass: only for the deliberately wrong model of the tests."""

    def __init__(self, p, slider_mass_factors=(1.0, 1.0, 1.0)):
        self.p = dict(p)
        lb, beta = p["lb"], p["beta"]
        self.u = np.array([[np.cos(t), np.sin(t), 0.0] for t in ACTUATOR_AZIMUTH])
        self.h = np.array([lb * np.array([np.sin(beta) * np.cos(p["alpha"] + k),
                                          np.sin(beta) * np.sin(p["alpha"] + k),
                                          np.cos(beta)]) for k in SLIDER_AZIMUTH])
        self.b = np.array([p["ld"] * np.array([np.cos(p["gamma"] + m),
                                               np.sin(p["gamma"] + m), 0.0])
                           for m in PLATFORM_AZIMUTH])
        self.P = np.array([0.0, 0.0, p["lp"]])
        a = p["a"]

        model = pin.Model()
        model.gravity = pin.Motion(np.array([0.0, 0.0, -p["g"]]), np.zeros(3))
        com = np.array([p[n] for n in COM])
        platform = model.addJoint(0, pin.JointModelSpherical(), pin.SE3(np.eye(3), self.P),
                                  "platform")
        inertia_com = tensor(p) - p["platformMass"] * (com @ com * np.eye(3) - np.outer(com, com))
        model.appendBodyToJoint(platform, pin.Inertia(p["platformMass"], com, inertia_com),
                                pin.SE3.Identity())
        # Each leg's universal joint: a horizontal first axis a1 perpendicular to the
        # leg's direction n0 at R = 1 (thz = 0: outside the stroke, but assembled), the
        # second axis n0 x a1. The joint is singular with the leg along a1; the legs
        # are steep (n_z > 0.7 over the workspace), so |n . a1| stays below 0.3 there
        # (configuration() refuses 0.9).
        level = self.legs(np.eye(3))
        self.sliders, self.leg_joints, self.tips, self.anchors, self.closures = [], [], [], [], []
        for i in range(3):
            slider = model.addJoint(0, pin.JointModelPrismaticUnaligned(self.u[i]),
                                    pin.SE3(np.eye(3), self.h[i]), f"slider{i + 1}")
            slider_mass = p["sliderMass"] * slider_mass_factors[i]
            model.appendBodyToJoint(slider, pin.Inertia(slider_mass, np.zeros(3),
                                                        np.zeros((3, 3))),
                                    pin.SE3.Identity())
            n0 = level[1][i]
            a1 = np.cross([0.0, 0.0, 1.0], n0)
            a1 /= np.linalg.norm(a1)
            frame = np.column_stack([a1, np.cross(n0, a1), n0])
            first = model.addJoint(slider, pin.JointModelRX(), pin.SE3(frame, np.zeros(3)),
                                   f"leg{i + 1}_u1")
            leg = model.addJoint(first, pin.JointModelRY(), pin.SE3.Identity(),
                                 f"leg{i + 1}_u2")
            t = p["legTransverseInertia"]
            model.appendBodyToJoint(
                leg, pin.Inertia(p["legMass"], np.array([0.0, 0.0, p["legComFraction"] * a]),
                                 np.diag([t, t, 0.0])), pin.SE3.Identity())
            tip = pin.SE3(np.eye(3), np.array([0.0, 0.0, a]))
            anchor = pin.SE3(np.eye(3), self.b[i])
            self.tips.append(model.addFrame(pin.Frame(f"tip{i + 1}", leg, tip,
                                                      pin.FrameType.OP_FRAME)))
            self.anchors.append(model.addFrame(pin.Frame(f"anchor{i + 1}", platform, anchor,
                                                         pin.FrameType.OP_FRAME)))
            self.sliders.append(slider)
            self.leg_joints.append((first, leg, frame))
            self.closures.append(pin.RigidConstraintModel(
                pin.ContactType.CONTACT_3D, model, leg, tip, platform, anchor,
                pin.ReferenceFrame.LOCAL))
        self.model, self.data = model, model.createData()
        self.platform = platform
        self.closure_models = pin.StdVec_RigidConstraintModel()
        for c in self.closures:
            self.closure_models.append(c)
        self.closure_datas = pin.StdVec_RigidConstraintData()
        for c in self.closures:
            self.closure_datas.append(c.createData())
        pin.initConstraintDynamics(model, self.data, self.closure_models, self.closure_datas)
        # Exact KKT solve (no proximal regularisation).
        self.prox = pin.ProximalSettings(1e-14, 0.0, 1)
        self.iv_platform = np.arange(model.joints[platform].idx_v,
                                     model.joints[platform].idx_v + 3)
        self.iv_slider = np.array([model.joints[j].idx_v for j in self.sliders])
        self.iv_rest = np.setdiff1d(np.arange(model.nv), self.iv_platform)

    # -- kinematics -------------------------------------------------------------------
    def legs(self, R):
        """Slider coordinates l and leg directions n at platform orientation R: the leg
        constraint |P + R b_i - h_i - l_i u_i| = a solved for l_i (the smaller root, this
        robot's assembly; docs/3pss-model.md)."""
        a = self.p["a"]
        ls, ns = np.zeros(3), np.zeros((3, 3))
        for i in range(3):
            d = self.P + R @ self.b[i] - self.h[i]
            du = d @ self.u[i]
            disc = du * du - d @ d + a * a
            if disc < 0:
                raise ValueError(f"leg {i + 1} cannot reach the platform")
            ls[i] = du - np.sqrt(disc)
            ns[i] = (d - ls[i] * self.u[i]) / a
        return ls, ns

    def configuration(self, theta):
        """Pinocchio's q at Euler angles theta (rad): the platform quaternion, the
        sliders and the legs' universal-joint angles."""
        R = pin.rpy.rpyToMatrix(np.asarray(theta, float))
        l, n = self.legs(R)
        q = np.zeros(self.model.nq)
        j = self.model.joints[self.platform]
        q[j.idx_q:j.idx_q + 4] = pin.Quaternion(R).coeffs()  # (x, y, z, w)
        for i in range(3):
            q[self.model.joints[self.sliders[i]].idx_q] = l[i]
            first, leg, frame = self.leg_joints[i]
            # R_frame Rx(q1) Ry(q2) e_z = n: Rx(q1) Ry(q2) e_z = (s2, -s1 c2, c1 c2).
            x, y, z = frame.T @ n[i]
            if abs(x) > 0.9:
                raise ValueError(f"leg {i + 1} near its universal joint's singularity")
            q[self.model.joints[leg].idx_q] = np.arcsin(x)
            q[self.model.joints[first].idx_q] = np.arctan2(-y, z)
        return q, R, l

    def closure_terms(self, q, v):
        """Closure Jacobian Jc (tip minus anchor velocity, in {A}) and its drift, the
        classical acceleration of tip minus anchor at zero joint acceleration."""
        model, data = self.model, self.data
        pin.forwardKinematics(model, data, q, v, np.zeros(model.nv))
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        world = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
        rows, drift = [], []
        for tip, anchor in zip(self.tips, self.anchors):
            rows.append(pin.getFrameJacobian(model, data, tip, world)[:3]
                        - pin.getFrameJacobian(model, data, anchor, world)[:3])
            drift.append(pin.getFrameClassicalAcceleration(model, data, tip, world).linear
                         - pin.getFrameClassicalAcceleration(model, data, anchor, world).linear)
        return np.vstack(rows), np.concatenate(drift)

    def closure_gap(self, q):
        """Largest distance between a leg's end and its platform joint, m."""
        pin.framesForwardKinematics(self.model, self.data, q)
        return max(np.linalg.norm(self.data.oMf[t].translation - self.data.oMf[a].translation)
                   for t, a in zip(self.tips, self.anchors))

    def point(self, theta, omega):
        """Everything at the plant state (theta, omega in {A})."""
        q, R, l = self.configuration(theta)
        Jc, _ = self.closure_terms(q, np.zeros(self.model.nv))
        # Admissible velocities: the platform's v is R^T omega; the rest follows from
        # Jc v = 0.
        G = np.zeros((self.model.nv, 3))
        G[self.iv_platform] = R.T
        G[self.iv_rest] = -np.linalg.solve(Jc[:, self.iv_rest], Jc[:, self.iv_platform] @ R.T)
        v = G @ np.asarray(omega, float)
        _, drift = self.closure_terms(q, v)
        E = pin.rpy.computeRpyJacobian(np.asarray(theta, float), pin.ReferenceFrame.WORLD)
        J = G[self.iv_slider]
        return Point(q, v, R, E, l, v[self.iv_slider], J, G, Jc, drift)

    # -- dynamics ---------------------------------------------------------------------
    def loads(self, pt, inputs):
        """The plant's inputs, friction and end stops as Pinocchio loads, two ways:

        - `tau`: generalized forces only: actuatorForce, the commanded torque
          realised by the actuators (f_c = J^-T (torqueCommand + E^-T
          generalizedForceCommand)), the stop forces and slider friction on the sliders'
          coordinates; disturbanceTorque and pivot friction as the platform joint's
          generalized force (the moment in the platform frame, R^T tau);
        - `tau_joints` plus `fext`: the commands as a moment on the platform
          (equal virtual power to f_c), disturbance and stop forces as external forces
          (pin.Force in each joint's frame).
        """
        p, R = self.p, pt.R
        f = np.asarray(inputs.get("actuatorForce", np.zeros(3)), float)
        commanded = (np.asarray(inputs.get("torqueCommand", np.zeros(3)), float)
                     + np.linalg.solve(pt.E.T, np.asarray(
                         inputs.get("generalizedForceCommand", np.zeros(3)), float)))
        disturbance = np.asarray(inputs.get("disturbanceTorque", np.zeros(3)), float)
        f_c = np.linalg.solve(pt.J.T, commanded)
        stops = [stop_force(p, pt.l[i], pt.l_dot[i]) for i in range(3)]
        f_stop = np.array([s[0] for s in stops])
        omega_body = pt.v[self.iv_platform]
        friction_slider = -p["sliderFriction"] * pt.l_dot
        friction_pivot = -p["pivotFriction"] * omega_body

        tau = np.zeros(self.model.nv)
        tau[self.iv_slider] = f + f_c + f_stop + friction_slider
        tau[self.iv_platform] = R.T @ disturbance + friction_pivot

        tau_joints = np.zeros(self.model.nv)
        tau_joints[self.iv_slider] = f + friction_slider
        tau_joints[self.iv_platform] = friction_pivot
        fext = pin.StdVec_Force()
        for _ in range(self.model.njoints):
            fext.append(pin.Force.Zero())
        fext[self.platform] = pin.Force(np.zeros(3), R.T @ (disturbance + commanded))
        for i, joint in enumerate(self.sliders):
            # The slider joints' frames keep the orientation of {A}.
            fext[joint] = pin.Force(f_stop[i] * self.u[i], np.zeros(3))
        return dict(tau=tau, tau_joints=tau_joints, fext=fext, force=f + f_c,
                    stop=f_stop, stop_energy=sum(s[1] for s in stops))

    def accelerations(self, pt, loads):
        """Joint accelerations by pin.constraintDynamics (from `tau`) and by the KKT
        system written out (from `tau_joints` and `fext`)."""
        model, data = self.model, self.data
        a_pin = pin.constraintDynamics(model, data, pt.q, pt.v, loads["tau"],
                                       self.closure_models, self.closure_datas, self.prox)
        a_pin = np.array(a_pin)
        M = pin.crba(model, data, pt.q)
        M = np.triu(M) + np.triu(M, 1).T
        bias = pin.rnea(model, data, pt.q, pt.v, np.zeros(model.nv), loads["fext"])
        n, m = model.nv, pt.Jc.shape[0]
        kkt = np.zeros((n + m, n + m))
        kkt[:n, :n], kkt[:n, n:], kkt[n:, :n] = M, pt.Jc.T, pt.Jc
        rhs = np.concatenate([loads["tau_joints"] - bias, -pt.drift])
        a_kkt = np.linalg.solve(kkt, rhs)[:n]
        return a_pin, a_kkt

    def derivatives(self, theta, omega, inputs, route="constraintDynamics"):
        """The plant's state derivative (thetaDot, omegaDot) and outputs by Pinocchio."""
        pt = self.point(theta, omega)
        loads = self.loads(pt, inputs)
        a_pin, a_kkt = self.accelerations(pt, loads)
        acc = a_pin if route == "constraintDynamics" else a_kkt
        omega_a = pt.R @ pt.v[self.iv_platform]
        return dict(
            thetaDot=np.linalg.solve(pt.E, omega_a),
            omegaDot=pt.R @ acc[self.iv_platform],  # d/dt (R w_B) = R w_B_dot
            omegaDot_kkt=pt.R @ a_kkt[self.iv_platform],
            omegaDot_pin=pt.R @ a_pin[self.iv_platform],
            l=pt.l, lDot=pt.l_dot, force=loads["force"], stopForce=loads["stop"],
            kineticEnergy=pin.computeKineticEnergy(self.model, self.data, pt.q, pt.v),
            potentialEnergy=pin.computePotentialEnergy(self.model, self.data, pt.q)
            + loads["stop_energy"],
            detJ=np.linalg.det(pt.J), condJ=np.linalg.cond(pt.J),
            # The Euler-angle generalized force that holds the pose at rest.
            gravityCompensation=self.computed_torque(theta, np.zeros(3), np.zeros(3)),
            closure_gap=self.closure_gap(pt.q),
            closure_velocity=np.max(np.abs(pt.Jc @ pt.v)),
        )

    def rhs(self, theta, omega, inputs):
        """(thetaDot, omegaDot) as one 6-vector (the plant's state derivative), by
        pin.constraintDynamics only."""
        pt = self.point(theta, omega)
        a = pin.constraintDynamics(self.model, self.data, pt.q, pt.v,
                                   self.loads(pt, inputs)["tau"], self.closure_models,
                                   self.closure_datas, self.prox)
        omega_a = pt.R @ pt.v[self.iv_platform]
        return np.concatenate([np.linalg.solve(pt.E, omega_a),
                               pt.R @ np.asarray(a)[self.iv_platform]])

    def computed_torque(self, theta, theta_dot, theta_ddot):
        """The Euler-angle generalized force that gives the platform the Euler-angle
        acceleration theta_ddot at (theta, theta_dot) against this model's inertia,
        velocity terms, gravity and friction: constrained inverse dynamics. The joint
        accelerations follow from the closures, pin.rnea gives the generalized forces
        of the open tree, and their projection on the admissible velocities (G^T,
        which annihilates the closure forces) is the moment in {A}; E^T makes it an
        Euler-angle generalized force (equal virtual power)."""
        theta = np.asarray(theta, float)
        E = pin.rpy.computeRpyJacobian(theta, pin.ReferenceFrame.WORLD)
        omega = E @ theta_dot
        # omega_dot = E theta_ddot + E_dot theta_dot (pin.rpy's time derivative).
        E_dot = pin.rpy.computeRpyJacobianTimeDerivative(theta, theta_dot,
                                                         pin.ReferenceFrame.WORLD)
        omega_dot = E @ theta_ddot + E_dot @ theta_dot
        pt = self.point(theta, omega)
        a = np.zeros(self.model.nv)
        a[self.iv_platform] = pt.R.T @ omega_dot
        # Jc a + drift = 0 for the remaining coordinates.
        a[self.iv_rest] = -np.linalg.solve(pt.Jc[:, self.iv_rest],
                                           pt.Jc[:, self.iv_platform] @ a[self.iv_platform]
                                           + pt.drift)
        tau = np.array(pin.rnea(self.model, self.data, pt.q, pt.v, a))
        tau[self.iv_slider] += self.p["sliderFriction"] * pt.l_dot
        tau[self.iv_platform] += self.p["pivotFriction"] * pt.v[self.iv_platform]
        return E.T @ (pt.G.T @ tau)
