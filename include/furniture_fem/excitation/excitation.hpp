#pragma once
// furniture_fem/excitation/excitation.hpp: the ground motion that drives the shake table.
//
// A Record is one component of acceleration, uniformly sampled; a TableMotion is the table's X (and
// optionally Y, Z) acceleration as a function of time, ready for Simulation::set_table_acceleration.
// Readers cover the formats strong-motion data come in (PEER NGA AT2, K-NET/KiK-net ASCII, JMA CSV,
// plain columns); processing covers what a record needs before it drives a model (resampling,
// baseline correction, zero-phase low-pass, windowing, integration); response spectra use the exact
// piecewise-linear recurrence; seeded synthetic motions are the toolkit's default input.
// Everything inside is SI: m/s^2, m/s, m, s. See docs/excitation/ground_motions.md.
// The parts, each a header of its own:
#include "record.hpp"
#include "record_io.hpp"
#include "processing.hpp"
#include "spectrum.hpp"
#include "seismic_intensity.hpp"
#include "synthetic.hpp"
