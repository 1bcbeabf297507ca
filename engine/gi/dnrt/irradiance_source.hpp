#pragma once
// Where DNRT's c_j come from: the incident-light service (engine/gi/incident) — the probes'
// indirect light at an object's centre (paper §5.2.1, "sampling and interpolating the coefficients
// of the light probes closest to O") plus the level's lights projected into SH there (§5.3: Unity's
// probes carry baked lights' direct light too). The names below are the service's, kept here for
// DNRT's code and tests: IrradianceSource is incident::IndirectSource.
#include "engine/gi/incident/incident.hpp"

namespace bounce::gi::dnrt {

using IrradianceSource = incident::IndirectSource;
using incident::ConstantEnvironment;
using incident::irradianceSH;

}  // namespace bounce::gi::dnrt
