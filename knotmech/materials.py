r"""Rope materials: effective axial modulus and density of the ropes people tie.

Every number the hold verdict takes from a material is defined here, once, with its
source. ``E`` is the rope's *effective* axial modulus, the slope of its working
load-strain curve divided by the nominal area :math:`A = \pi d^2/4` (so that
:math:`EA` is the rope's axial stiffness and :math:`T/EA` its strain), not the
modulus of the fibre: a rope is part air and its fibres lie on helices, so its
effective modulus is a fraction (roughly 0.1 to 0.7) of the fibre's. Ropes are
visco-elastic and stiffen after bedding in and under cyclic load; each preset gives a
nominal value for a used, bedded-in rope at working loads (10-30 % of break) and the
range over constructions (``E_range``). ``density`` is the apparent density, mass
per length over :math:`\pi d^2/4`.

Each preset also carries a **bending scale** :math:`\kappa` (``bending_scale``): the
rope's bending stiffness is :math:`B = \kappa\, E \pi d^4/64`, :math:`\kappa = 1` for a
solid rod. A rope's fibres and yarns slide on one another when it bends, so it bends
far more easily than a solid rod of its diameter and axial modulus. No rope-level
bending measurement with a number we could read was found for these ropes (the searches
and the two papers that did measure rope bending, on a 3x7 steel wire rope and on
polyethylene ropes, are listed in docs/notes/ropek.md); the fibre-rope values are
ESTIMATES from the full-slip bound of a rope of :math:`N` independent, equal yarns
or strands of diameter :math:`d_y`, :math:`\pi N d_y^2/4 = \phi\, \pi d^2/4` (packing
:math:`\phi`): :math:`B = N E_y \pi d_y^4/64` with the yarn modulus
:math:`E_y = E/\phi`, i.e. :math:`\kappa \approx \phi/N`, and :math:`N` the number of
load-bearing yarn bundles that bend independently (a yarn is itself a bundle of
filaments and bends more easily still, so this is an upper estimate for a slack rope;
friction between yarns under tension raises it). Order of magnitude: 0.01, range
0.003-0.05. Give ``--bending-scale`` for a measured rope.

Presets and sources (conversions: 1 kgf = 9.80665 N, 1 lbf = 4.44822 N):

``nylon`` (polyamide kernmantle, climbing/rescue rope)
    E = 0.25 GPa, range 0.1-0.4 GPa. EN 1891 type A (low-stretch kernmantle,
    d >= 10 mm): at most 5 % elongation between a 50 kg and a 150 kg load, i.e.
    E >= 981 N / (0.05 x 78.5 mm^2) = 0.25 GPa at 10 mm (typical ropes 3-4 %:
    about 0.3-0.4 GPa); EN 892 dynamic ropes stretch up to about 8-10 % under
    80 kg (10 mm: E about 0.1 GPa). Summary of both standards:
    https://manual.besafety.co.uk/chapters/equipment/ropes. Density 800 kg/m^3
    (a 10 mm kernmantle rope weighs about 62-65 g/m: 790-830 kg/m^3 on 78.5 mm^2;
    nylon SG 1.14, Marlow Ropes physical-properties table, at a packing of 0.7).
    kappa = 0.01 (estimate, range 0.003-0.03): a 10 mm kernmantle rope has a core of
    about 7-12 plied strands of 5-10 yarns each and a 32-48 carrier sheath; about 60
    independent bundles at packing 0.7: kappa = 0.7 / 60 = 0.012.
``polyester`` (polyester double braid / 3-strand)
    E = 2 GPa, range 1-6 GPa. Polyester yarn specific modulus 10 N/tex (Flory,
    Tension Technology International, "Synthetic fibre yarn properties", Table 1),
    i.e. 13.8 GPa on the fibre (SG 1.38); a rope at a packing of 0.6 and a
    construction efficiency of 0.15-0.7 gives 1.2-6 GPa (laid and braided ropes at
    the low end, parallel-yarn mooring ropes at the high end). Density 830 kg/m^3
    (SG 1.38 x packing 0.6).
    kappa = 0.01 (estimate, range 0.003-0.03): a double braid (16-24 carriers in each
    of core and cover, each of several yarns), about 50 bundles at packing 0.6: 0.012.
``hmpe`` (Dyneema / Spectra 12-strand braid; alias ``dyneema``)
    E = 40 GPa, range 20-90 GPa. HMPE yarn 124 N/tex (TTI Table 1, Spectra 900 /
    Dyneema), 120 GPa on the fibre (SG 0.97); packing 0.6 and construction
    efficiency 0.3-0.8 give 22-58 GPa for ordinary 12-strand braids. Heat-treated
    braids are stiffer: a measured 9 mm DynIce Dux stretched 0.00078 per 1000 lbf
    after 50 cycles to 20 % of break, E = 4448 N / 0.00078 / 63.6 mm^2 = 90 GPa
    (https://www.catsailor.com/forum/ubbthreads.php/posts/170007, which also
    quotes 0.00055 per 1000 lbf at 11 mm, 85 GPa). Density 580 kg/m^3 (SG 0.97
    Marlow x 0.6).
    kappa = 0.01 (estimate, range 0.005-0.05): 12 strands of 4-8 yarns each, about
    60 bundles at packing 0.6: 0.01; heat-set braids are stiffer (upper end).
``manila`` (abaca, 3-strand laid)
    E = 1 GPa, range 0.5-2 GPa: an estimate with the least support of the presets
    (no rope-level load-strain data was found; hard-fibre ropes are described as
    stretching little, e.g. https://www.jbropesupply.com/which-rope-is-right-for-you/,
    and laid natural-fibre ropes take 10-20 % of a fibre modulus of the order of
    10-30 GPa). Density 880 kg/m^3 (1/2 in manila, about 7.5 lb per 100 ft;
    approximate). Give ``--youngs-modulus`` for a measured rope. kappa = 0.02
    (estimate, range 0.01-0.05): 3 strands of about 10 coarse yarns each, 30 bundles
    at packing 0.65: 0.022; hard fibre and a hard lay put it above the synthetics.
``polypropylene`` (3-strand or braided; alias ``pp``)
    E = 1 GPa, range 0.5-3 GPa. PP yarn 3.5 N/tex (multifilament) to 8 N/tex
    (monofilament) (TTI Table 1), 3.2-7.3 GPa on the fibre (SG 0.91); packing 0.6
    and construction efficiency 0.25-0.7. Density 550 kg/m^3 (SG 0.91 x 0.6).
    kappa = 0.02 (estimate, range 0.005-0.05): 3 strands of 8-12 yarns (often coarse
    monofilament or split-film, stiffer than multifilament), about 30 bundles at 0.6.
``steel-wire`` (6x19 stranded steel wire rope; alias ``steel``)
    E = 49 GPa, range 30-60 GPa on the nominal area. Elastic stretch of a 16 mm
    6x19 rope: load [tonne-f] / 10 per cent, i.e. EA = 9.81 MN, E = 9.81 MN /
    201 mm^2 = 49 GPa; 6x24 gives 39 GPa and 6x12 (fibre centres) 29 GPa
    (http://marinegyaan.com/what-is-meaning-of-elastic-stretch-of-wire/). The
    modulus on the metallic area is about 100-112 GPa (e.g. 111.8 GPa computed for
    a 32 mm rope, http://calqlata.com/productpages/00044-QandA.html), times a
    metallic fill factor of about 0.45-0.55. Density 4390 kg/m^3 (6x7 fibre core,
    16 mm: 88.3 kg per 100 m, API Spec 9A, Table C.1).
    kappa = 0.02 (estimate, range 0.009-0.1): the full-slip bound is the sum of the
    wires' own EI, 114 wires of about d/15 and 200 GPa: kappa_min =
    114 (1/15)^4 x 200 / 49 = 0.0092; friction between wires under tension raises the
    effective value towards a small multiple of that (the no-slip bound, the wires stuck
    as a solid, is kappa of order 1). Bounds EI_min (independent wires) and EI_max
    (solid) as in A. Cardou's review "Taut helical strand bending stiffness" and
    Paradis & Legeron (multilayer cable free bending); see docs/notes/ropek.md.
``vps32`` (the clove-hitch paper's silicone rod)
    E = 1.26 MPa, density 1160 kg/m^3: vinylpolysiloxane (VPS32, Elite Double 32,
    Zhermack), clove-hitch paper (Extreme Mech. Lett., DOI
    10.1016/j.eml.2022.101788), sec. 2. A solid elastic rod, not a rope: E is the
    material's. The shipped DER phase tables were computed for this rod (with a
    density of 1150 kg/m^3: a protocol second is sqrt(1160/1150) = 1.004 s for the preset,
    :func:`knotmech.scenes.phase_table.protocol_time_scale`). kappa = 1: a solid
    rod (exact by construction; the tables' meta has no ``bending_scale``, i.e. 1).

The reference rods of the source papers (VPS32, the clove-hitch scene's rod geometry, the
implicit-contact-model paper's rod, the coated-rod paper's rubber rod, the tables' density)
are module constants below, each with its source: import them, do not retype them.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from knotmech.errors import InputError

__all__ = [
    "Material",
    "MATERIALS",
    "material",
    "material_names",
    "format_modulus",
    "VPS32",
    "VPS32_YOUNGS_MODULUS",
    "VPS32_DENSITY",
    "CLOVE_ROD_DIAMETER",
    "CLOVE_ROD_TAIL",
    "CLOVE_ROD_EDGE",
    "PHASE_TABLE_DENSITY",
    "IMC_YOUNGS_MODULUS",
    "IMC_DENSITY",
    "COATED_YOUNGS_MODULUS",
    "COATED_ROD_DIAMETER",
    "COATED_DENSITY",
    "DEMO_ROD_YOUNGS_MODULUS",
    "DEMO_ROD_DENSITY",
    "STRAIN_LIMIT",
]

#: the largest strain T/EA the models here take a rope to [-]: above it a load is implausible
#: for rope (the hold verdict warns), the thick-nip model (inextensible rope) is outside its
#: validity, and a DER pull of a bend or a loop stops (the rod model has a linear axial law)
STRAIN_LIMIT = 0.10

# --- the reference rods of the source papers (one home for each number) ----------------
# Every rod the scenes, validations, benchmarks and tests simulate with a paper's numbers
# takes them from here. Where two numbers were used for what looks like one rod, both are
# named below with what each one is.

#: [Pa] VPS32 (Elite Double 32, Zhermack): clove-hitch paper (Extreme Mech. Lett., DOI
#: 10.1016/j.eml.2022.101788), sec. 2 (a): "Young's modulus E = 1.26 MPa, density
#: rho = 1160 kg/m^3"
VPS32_YOUNGS_MODULUS = 1.26e6
#: [kg/m^3] VPS32's density, same place (the only density either paper states for VPS32;
#: the coated-rod paper's rod is natural rubber and states none)
VPS32_DENSITY = 1160.0
#: [m] the clove-hitch paper's rod diameter for the mechanical tests (sec. 2, sec. 4)
CLOVE_ROD_DIAMETER = 4e-3
#: [m] straight tail at each end of the clove-hitch scene's rod (the paper's L = 374 mm
#: at D = 30 mm: 374 mm less the wraps)
CLOVE_ROD_TAIL = 0.064
#: [m] rest edge length of the clove-hitch scene's rod (120 nodes on 374 mm)
CLOVE_ROD_EDGE = 0.374 / 119
#: [kg/m^3] the density the shipped DER clove-hitch phase tables (``clove_phase_table*.json``)
#: were computed with: NOT a measured value (VPS32 is 1160 kg/m^3), kept because the
#: tables are golden; ``knotmech.scenes.phase_table.protocol_time_scale`` converts
#: (a protocol second is sqrt(1160/1150) = 1.004 s of the VPS32 rod)
PHASE_TABLE_DENSITY = 1150.0
#: [Pa] the implicit-contact-model paper's rod (Choi, Tong & Jawed, J. Appl. Mech. 88,
#: 051010, 2021; its option file): E = 0.18 MPa (another rod than VPS32)
IMC_YOUNGS_MODULUS = 0.18e6
#: [kg/m^3] its density, same option file
IMC_DENSITY = 1180.0
#: [Pa] the coated-rod paper's rod (J. Appl. Mech., DOI 10.1115/1.4055544), sec. 3.1:
#: natural rubber, E = 1.83 MPa, d = 1/16 in
COATED_YOUNGS_MODULUS = 1.83e6
#: [m] its diameter, 1/16 in (the paper: "1.59 mm approximately")
COATED_ROD_DIAMETER = 1.59e-3
#: [kg/m^3] natural rubber, ASSUMED: the paper gives no density (inertia is negligible at
#: its pull speeds)
COATED_DENSITY = 930.0
#: [Pa] the soft rod of the bend scenes' defaults (and the centreline tests): NOT a paper's rod, a
#: round generic elastomer (E = 1 MPa) for demonstrations and tests
DEMO_ROD_YOUNGS_MODULUS = 1.0e6
#: [kg/m^3] its density (a generic silicone rubber, 1100 kg/m^3; no source)
DEMO_ROD_DENSITY = 1100.0


@dataclass(frozen=True)
class Material:
    """A rope (or rod) material preset.

    Attributes
    ----------
    key : str
        Name used by ``--material`` / ``material=``.
    description : str
    youngs_modulus : float
        Effective axial modulus E on the nominal area :math:`\\pi d^2/4` [Pa].
    youngs_modulus_range : tuple of float
        (low, high) over constructions [Pa].
    density : float
        Apparent density, mass per length over :math:`\\pi d^2/4` [kg/m^3].
    source : str
        Where the numbers come from (details in the module docstring).
    bending_scale : float
        kappa: bending stiffness B = kappa E pi d^4 / 64 (1 for a solid rod; an estimate
        for the ropes, see the module docstring).
    bending_scale_range : tuple of float
        (low, high) estimate of kappa over constructions.
    bending_source : str
        Where kappa comes from.
    """

    key: str
    description: str
    youngs_modulus: float
    youngs_modulus_range: tuple
    density: float
    source: str
    bending_scale: float = 1.0
    bending_scale_range: tuple = (1.0, 1.0)
    bending_source: str = "solid rod"

    def to_dict(self) -> dict:
        d = asdict(self)
        d["youngs_modulus_range"] = list(self.youngs_modulus_range)
        d["bending_scale_range"] = list(self.bending_scale_range)
        return d


VPS32 = Material(
    "vps32",
    "VPS32 silicone rod (the clove-hitch paper's; the DER tables' material)",
    VPS32_YOUNGS_MODULUS,
    (VPS32_YOUNGS_MODULUS, VPS32_YOUNGS_MODULUS),
    VPS32_DENSITY,
    "clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788), sec. 2",
    1.0,
    (1.0, 1.0),
    "solid elastic rod: B = E pi d^4 / 64 exactly",
)

_EST = "estimate: full-slip bound kappa ~ packing / N independent yarn bundles"

#: every preset, by key (see the module docstring for the sources)
MATERIALS: dict[str, Material] = {
    m.key: m
    for m in (
        Material(
            "nylon",
            "nylon (polyamide) kernmantle rope",
            0.25e9,
            (0.1e9, 0.4e9),
            800.0,
            "EN 1891 type A (<= 5 % between 50 and 150 kg) and EN 892 (about 8-10 % "
            "under 80 kg) elongation limits",
            0.01,
            (0.003, 0.03),
            _EST + " (about 60 at 0.7)",
        ),
        Material(
            "polyester",
            "polyester rope (double braid or 3-strand)",
            2.0e9,
            (1.0e9, 6.0e9),
            830.0,
            "yarn 10 N/tex (Flory, TTI yarn table 1) x packing 0.6 x construction 0.15-0.7",
            0.01,
            (0.003, 0.03),
            _EST + " (about 50 at 0.6)",
        ),
        Material(
            "hmpe",
            "HMPE (Dyneema, Spectra) 12-strand braid",
            40e9,
            (20e9, 90e9),
            580.0,
            "yarn 124 N/tex (TTI table 1) x packing 0.6 x construction 0.3-0.8; heat-treated "
            "9 mm braid measured at 90 GPa",
            0.01,
            (0.005, 0.05),
            _EST + " (12 strands x 4-8 yarns at 0.6)",
        ),
        Material(
            "manila",
            "manila (abaca) 3-strand laid rope",
            1.0e9,
            (0.5e9, 2.0e9),
            880.0,
            "estimate (no rope-level load-strain data found); give --youngs-modulus",
            0.02,
            (0.01, 0.05),
            _EST + " (3 strands x about 10 yarns at 0.65)",
        ),
        Material(
            "polypropylene",
            "polypropylene rope",
            1.0e9,
            (0.5e9, 3.0e9),
            550.0,
            "yarn 3.5-8 N/tex (TTI table 1) x packing 0.6 x construction 0.25-0.7",
            0.02,
            (0.005, 0.05),
            _EST + " (3 strands x 8-12 yarns at 0.6)",
        ),
        Material(
            "steel-wire",
            "6x19 stranded steel wire rope",
            49e9,
            (30e9, 60e9),
            4390.0,
            "elastic stretch of 16 mm 6x19 rope (load in tonne-f / 10 per cent); API Spec 9A "
            "table C.1 mass",
            0.02,
            (0.009, 0.1),
            "estimate: full-slip bound 114 wires of d/15 at 200 GPa gives 0.0092; "
            "inter-wire friction raises it",
        ),
        VPS32,
    )
}

_ALIASES = {
    "polyamide": "nylon",
    "kernmantle": "nylon",
    "nylon-kernmantle": "nylon",
    "pes": "polyester",
    "dacron": "polyester",
    "dyneema": "hmpe",
    "spectra": "hmpe",
    "uhmwpe": "hmpe",
    "abaca": "manila",
    "pp": "polypropylene",
    "steel": "steel-wire",
    "wire": "steel-wire",
    "steel-wire-rope": "steel-wire",
    "wire-rope": "steel-wire",
    "silicone": "vps32",
}


def material_names() -> tuple[str, ...]:
    """The preset keys, in the order of :data:`MATERIALS`."""
    return tuple(MATERIALS)


def material(name) -> Material:
    """The preset called ``name`` (case-insensitive; spaces, ``_`` and ``-`` alike).

    Raises
    ------
    InputError
        Unknown name; the one-line message lists the known presets.
    """
    if isinstance(name, Material):
        return name
    key = str(name).strip().lower().replace("_", "-").replace(" ", "-").replace("/", "-")
    key = _ALIASES.get(key, key)
    if key not in MATERIALS:
        raise InputError(
            f"unknown material {str(name)!r}; known: {', '.join(MATERIALS)} "
            "(or give --youngs-modulus)"
        )
    return MATERIALS[key]


def format_modulus(value: float) -> str:
    """A modulus in Pa for people: ``1.26 MPa``, ``0.25 GPa``, ``49 GPa``."""
    v = float(value)
    if v >= 1e8:
        return f"{v / 1e9:.3g} GPa"
    if v >= 1e5:
        return f"{v / 1e6:.3g} MPa"
    return f"{v:.3g} Pa"
