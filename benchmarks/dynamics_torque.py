"""Benchmark line (not a test): the four-bar driving torque at 10^6 crank angles vs its full kinematics
(angles, speeds, accelerations) in the generated NumPy module. Run: python benchmarks/dynamics_torque.py."""
import time

import numpy


def main() -> None:
    from symlink.catalog import fourbar
    from symlink.dynamics import DynamicModel, MassProperties, Gravity
    from symlink.scene import Scene
    model = DynamicModel(fourbar(), [MassProperties("crank", "m2", "r2", 0, "I2"), MassProperties("coupler", "m3", "r3", "d3", "I3"),
                                      MassProperties("rocker", "m4", "r4", 0, "I4")], gravity=Gravity(0, -9.81))
    values = dict(a=20., b=66., c=56., d=80., m2=1., r2=10., I2=5., m3=2., r3=30., d3=0.2, I3=40., m4=1.5, r4=28., I4=30.,
                  thetadot=10.5, thetaddot=0.)
    theta = numpy.linspace(0, 2 * numpy.pi, 10**6)
    kin = Scene(model.linkage, ["coupler", "rocker", "coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel"], values)
    tor = Scene(model.linkage, ["input_torque"], values)
    kf, tf = kin.code.function, tor.code.function
    def best(f):
        times = []
        for _ in range(3):
            t = time.perf_counter(); f(theta=theta, **values); times.append(time.perf_counter() - t)
        return min(times)
    k, t = best(kf), best(tf)
    print(f"kinematics {k:.3f}s torque {t:.3f}s ratio {t/k:.2f}")


if __name__ == "__main__":
    main()
