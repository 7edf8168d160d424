"""OpenQuake NRML 0.5 fragility models (the engine's documentation, "Fragility Models": a
fragilityModel with id, assetCategory and lossCategory, a description, the limit states, and per
function `<fragilityFunction id=... format="continuous" shape="logncdf">` holding
`<imls imt=... noDamageLimit=... minIML=... maxIML=.../>` and one `<params ls=... mean=...
stddev=.../>` per limit state).

A rock has one limit state, `overturned`. The engine's lognormal functions take the mean and
standard deviation of the capacity itself (linear units), not of its logarithm:
mean = theta exp(beta^2 / 2), stddev = mean sqrt(exp(beta^2) - 1).
"""
import math
import xml.etree.ElementTree as ET

NAMESPACE = "http://openquake.org/xmlns/nrml/0.5"
LIMIT_STATE = "overturned"


def lognormal_moments(theta, beta):
    mean = theta * math.exp(0.5 * beta * beta)
    return mean, mean * math.sqrt(math.expm1(beta * beta))


def fragility_model(model_id, description, functions, asset_category="buildings", loss_category="structural"):
    """The NRML document as an ElementTree. functions: dicts with id, theta_g, beta, min_iml,
    max_iml, no_damage_limit."""
    ET.register_namespace("", NAMESPACE)
    root = ET.Element(f"{{{NAMESPACE}}}nrml")
    model = ET.SubElement(root, f"{{{NAMESPACE}}}fragilityModel",
                          {"id": model_id, "assetCategory": asset_category, "lossCategory": loss_category})
    ET.SubElement(model, f"{{{NAMESPACE}}}description").text = description
    ET.SubElement(model, f"{{{NAMESPACE}}}limitStates").text = LIMIT_STATE
    for fn in functions:
        el = ET.SubElement(model, f"{{{NAMESPACE}}}fragilityFunction",
                           {"id": fn["id"], "format": "continuous", "shape": "logncdf"})
        ET.SubElement(el, f"{{{NAMESPACE}}}imls",
                      {"imt": "PGA", "noDamageLimit": _num(fn["no_damage_limit"]),
                       "minIML": _num(fn["min_iml"]), "maxIML": _num(fn["max_iml"])})
        mean, stddev = lognormal_moments(fn["theta_g"], fn["beta"])
        ET.SubElement(el, f"{{{NAMESPACE}}}params", {"ls": LIMIT_STATE, "mean": _num(mean), "stddev": _num(stddev)})
    ET.indent(root, space="  ")
    return ET.ElementTree(root)


def _num(v):
    return repr(float(v))


def write(path, tree):
    tree.write(path, encoding="UTF-8", xml_declaration=True)
