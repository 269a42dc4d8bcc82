"""Rotor nondimensional units.

Everything inside the solvers is expressed in rotor units: length ``R``,
time ``1/Omega`` (so time is the azimuth ``psi``) and mass per length ``m0``.
``m0 = 3 I_b / R^3`` is the mass per length of the uniform blade that has the
same flap inertia ``I_b`` as the real one, so that the Lock number is
``gamma = rho a c R / m0 * 3`` and frequencies come out directly in /rev.

============================  ==========================
quantity                      divided by
============================  ==========================
length, displacement          R
mass per length               m0
bending/torsion stiffness     m0 Omega^2 R^4
axial stiffness EA            m0 Omega^2 R^2
mass moment per length        m0 R^2
spring (moment per angle)     m0 Omega^2 R^3
damper (moment*time/angle)    m0 Omega R^3
force per length              m0 Omega^2 R
============================  ==========================
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["RotorUnits"]


@dataclass(frozen=True)
class RotorUnits:
    """Reference scales of the rotor nondimensional system (all SI).

    Parameters
    ----------
    radius : float
        Rotor radius R [m].
    rotor_speed : float
        Reference rotor speed Omega [rad/s].
    mass_per_length : float
        Reference mass per length m0 [kg/m].

    Examples
    --------
    >>> u = RotorUnits(radius=2.0, rotor_speed=10.0, mass_per_length=3.0)
    >>> u.bending_stiffness(3.0 * 100.0 * 16.0)
    1.0
    """

    radius: float
    rotor_speed: float
    mass_per_length: float

    @property
    def energy(self) -> float:
        """Energy (and moment) scale m0 Omega^2 R^3 [J]."""
        return self.mass_per_length * self.rotor_speed**2 * self.radius**3

    def length(self, value):
        return value / self.radius

    def mass_per_len(self, value):
        return value / self.mass_per_length

    def bending_stiffness(self, value):
        return value / (self.energy * self.radius)

    def axial_stiffness(self, value):
        return value / (self.energy / self.radius)

    def inertia_per_length(self, value):
        return value / (self.mass_per_length * self.radius**2)

    def inertia(self, value):
        """A mass moment of inertia [kg m^2] in units of ``m0 R^3``."""
        return value / (self.mass_per_length * self.radius**3)

    def spring(self, value):
        return value / self.energy

    def damper(self, value):
        return value * self.rotor_speed / self.energy
