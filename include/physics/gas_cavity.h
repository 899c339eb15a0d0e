// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A gas enclosed in the cavity}
//
// Instead of a prescribed pressure the cavity may hold a gas: sealed at $t
// = 0$ with the gauge pressure $p_0$ (`Initial pressure`) in the volume
// $V_0$ of the initial state, then compressed and expanded by the motion of
// the walls, and fed by a mass inflow $\dot m(t)$ if the parameter file
// gives one. The gas law is the polytropic one of Abaqus' *FLUID CAVITY and
// FEBio's ideal-gas pressure load, written in the gas density $\rho =
// m/V$:
// @f[
//   P(V, t) = P_0\left(\frac{\rho}{\rho_0}\right)^{\gamma}
//   = P_0\left(\frac{m(t)}{m_0}\,\frac{V_0}{V}\right)^{\gamma},
//   \qquad m(t) = m_0 + \int_0^t\dot m\,ds,
// @f]
// with the absolute pressures $P = P_a + p$ ($P_a$ the ambient pressure;
// the walls are loaded by the gauge pressure $p$, the ambient pressure acts
// on both sides), $\gamma = 1$ for an isothermal gas and $1.4$ for air
// compressed adiabatically. $V$ is the whole volume the gas fills: the
// meshed cavity divided by the model fraction (the cavity of the whole
// physical body) plus the dead volume of tubing and valves. The initial
// density follows from the ideal gas, $\rho_0 = P_0/(R T_0)$ with $R =
// 287.05$ J/(kg K) of air; it matters only for the inflow, whose mass is
// measured against $m_0 = \rho_0 V_0$.
//
// For a fixed gas mass and $\gamma = 1.4$ the law is the isentrope of an
// ideal gas; with an inflow it is the isentrope of the gas in the cavity
// at its present mass, i.e. the inflowing gas is taken to arrive at the
// cavity's own specific entropy. For $\gamma = 1$ it is exact for an
// isothermal inflow.
//
// The pressure is a function of the state -- the displacement, through
// $V(\mathbf u)$, and the time, through $m(t)$ -- evaluated at the end of
// every time step as the displacement is, inside the Newton iteration.
// Nothing of it is integrated with the time step: the mass $m(t)$ is the
// integral of $\dot m$ on a fixed grid (1e-4 s, three-point Gauss on each
// interval), the same for every time step. Two runs with $\Delta t$ and
// $\Delta t/2$ therefore follow the same law, and differ only by the
// time-integration error of the motion (SOFA's pressure-controlled
// cavities, which update the pressure by the volume change of the last
// step, do not; the tests check ours).
//
// The derivative that the tangent needs is
// @f[
//   \frac{dp}{dV} = -\gamma\frac{P}{V} < 0 :
// @f]
// the gas is a spring, stiffer the smaller its volume.
//
// Implemented in source/physics/gas_cavity.cc.

#ifndef soft_robot_physics_gas_cavity_h
#define soft_robot_physics_gas_cavity_h

#include <core/parameters.h>
#include <physics/pressure_history.h>
#include <vector>

namespace SoftRobot
{
  class GasCavity
  {
  public:
    // The specific gas constant of air, J/(kg K), in the program's units
    // (mm^2 s^-2 K^-1).
    static constexpr double air_gas_constant = 287.05e6;

    explicit GasCavity(const Parameters::AllParameters &parameters);

    // Seals the cavity with the gas volume `volume` (mm^3, the whole body's,
    // dead volume included) at t = 0; an input error if it is not positive.
    // `cavity_volume` is the meshed part of it, for the message.
    void
    seal(const double volume, const double cavity_volume);

    bool
    is_sealed() const
    {
      return sealed_volume > 0.;
    }

    // The volume (mm^3) and mass (kg) at sealing, for a checkpoint, and the
    // seal restored from them at a restart.
    std::vector<double>
    sealed_state() const
    {
      return {sealed_volume, sealed_mass};
    }
    void
    restore_seal(const std::vector<double> &state);

    // The gauge pressure (kPa) of the gas at the volume V (mm^3) and time
    // t, and its derivative dp/dV; throws StepFailure for a volume or a
    // gas mass that is not positive.
    double
    gauge_pressure(const double volume, const double time) const;
    double
    pressure_derivative(const double volume, const double time) const;

    // The gas mass at time t, kg, and the mass at sealing.
    double
    mass(const double time) const;
    double
    initial_mass() const
    {
      return sealed_mass;
    }

    // The inflow expression evaluated at times spread over [0, end time]
    // (input errors naming the entry).
    void
    check(const double end_time) const;

  private:
    double
    absolute_pressure(const double volume, const double time) const;

    const std::string where;
    const double      ambient;
    const double      initial_absolute;
    const double      exponent;
    const double      temperature;
    const bool        has_inflow;
    PressureHistory   inflow;
    double            sealed_volume = 0.;
    double            sealed_mass   = 0.;
    // The integral of the inflow rate from 0 to k times the grid step.
    mutable std::vector<double> cumulative_inflow;
  };
} // namespace SoftRobot

#endif
