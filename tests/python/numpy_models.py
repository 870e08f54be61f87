"""Models written as vectorised numpy functions for glintlab.register_model: a Lambertian and
variants of it that are wrong on purpose (the tests of register_model use them)."""

import numpy as np

ALBEDO = {"name": "albedo", "default": 0.8, "lo": 0, "hi": 1,
          "description": "the fraction of the light reflected"}


def lambert_eval(q, p):
    """albedo cos θo / π (the cosine-weighted value), 0 below the horizon."""
    return p["albedo"] * np.maximum(q["wo_z"], 0) / np.pi


def lambert_pdf(q, p):
    """cos θo / π: the density of the cosine-weighted hemisphere sampler."""
    return np.maximum(q["wo_z"], 0) / np.pi


def lambert_sample(q, u, p):
    """Cosine-weighted hemisphere (Malley's method): weight = value / pdf = albedo."""
    r = np.sqrt(u[:, 0])
    phi = 2 * np.pi * u[:, 1]
    z = np.sqrt(np.maximum(0.0, 1 - u[:, 0]))
    wo = np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)
    return {"wo": wo, "pdf": z / np.pi, "weight": np.full(len(z), p["albedo"])}


def register_lambert(glintlab, name):
    glintlab.register_model(name, lambert_eval, lambert_pdf, lambert_sample, params=[ALBEDO],
                            description="Lambertian in numpy",
                            source="cosine-weighted hemisphere sampling (Malley's method)")


# The pdf 3 % above the sampler's density, everywhere it is reported (pdf(), the sample's pdf and
# its weight value/pdf agree with each other): only the sampled directions contradict it.
def wrong_pdf(q, p):
    return 1.03 * lambert_pdf(q, p)


def wrong_pdf_sample(q, u, p):
    s = lambert_sample(q, u, p)
    s["pdf"] = 1.03 * s["pdf"]
    s["weight"] = s["weight"] / 1.03
    return s


def register_wrong_pdf(glintlab, name):
    glintlab.register_model(name, lambert_eval, wrong_pdf, wrong_pdf_sample, params=[ALBEDO],
                            description="Lambertian whose pdf is 3 % above its sampler's density")
