#!/usr/bin/env python3
"""Checks a package's data/ro-crate-metadata.json with tools that are not Surrogate's.

Usage: ro_crate_check.py BAG CONTEXT_DIR

- Python's json module parses it (strict JSON).
- PyLD (Debian python3-pyld) expands it as JSON-LD with the RO-Crate 1.1 and workflow-run
  contexts kept in CONTEXT_DIR (no network): every property of every entity must expand to an
  IRI, since JSON-LD silently drops a term its context does not define.
- Every file under BAG/data (but the crate's own metadata) is a File entity in the root's
  hasPart, with its size and SHA-256 computed here with hashlib.
- Every step of the carrier (read here with xml.etree) is a HowToStep of the main workflow; each
  step with a result has a CreateAction whose instrument is a SoftwareApplication with the step's
  version, and a ControlAction; every local reference resolves to an entity of the graph.
- The root has a license (RO-Crate 1.1 requires it): an entity of the graph with a name.
- The root conforms to the Process, Workflow and Provenance Run Crate profiles 0.5 and its
  mainEntity is a File typed ComputationalWorkflow.
Prints one line per problem and exits 1, or prints a summary and exits 0.
"""
import hashlib
import json
import os
import sys
import xml.etree.ElementTree as ET

from pyld import jsonld

CONTEXTS = {
    "https://w3id.org/ro/crate/1.1/context": "ro-crate-1.1-context.jsonld",
    "https://w3id.org/ro/terms/workflow-run/context": "workflow-run-context.jsonld",
}
CARRIER = "{urn:surrogate:carrier:1}"


def main():
    bag, context_dir = sys.argv[1], sys.argv[2]
    problems = []
    with open(os.path.join(bag, "data", "ro-crate-metadata.json"), "rb") as f:
        crate = json.loads(f.read().decode("utf-8"))

    def loader(url, options=None):
        if url not in CONTEXTS:
            raise jsonld.JsonLdError("no network: " + url, "loading document failed", {"url": url})
        with open(os.path.join(context_dir, CONTEXTS[url]), encoding="utf-8") as f:
            return {"contentType": "application/ld+json", "contextUrl": None,
                    "documentUrl": url, "document": json.load(f)}

    expanded = jsonld.expand(crate, {"documentLoader": loader, "base": "arcp://name,surrogate/"})
    by_expanded_id = {node.get("@id"): node for node in expanded}
    graph = crate["@graph"]
    by_id = {}
    for entity in graph:
        if entity["@id"] in by_id:
            problems.append("entity %s is given twice" % entity["@id"])
        by_id[entity["@id"]] = entity
    for entity in graph:
        # The expanded node of this entity (ids resolved against the base).
        node_id = jsonld.prepend_base("arcp://name,surrogate/", entity["@id"])
        node = by_expanded_id.get(node_id)
        if node is None:
            problems.append("entity %s is lost in JSON-LD expansion" % entity["@id"])
            continue
        kept = len([k for k in node if not k.startswith("@")])
        given = len([k for k in entity if not k.startswith("@")])
        if kept != given:
            dropped = sorted(k for k in entity if not k.startswith("@") and
                             not any(e.endswith("/" + k) or e.endswith("#" + k) for e in node))
            problems.append("entity %s: %d of %d properties do not expand (%s)" %
                            (entity["@id"], given - kept, given, ", ".join(dropped)))
        for t in ([entity["@type"]] if isinstance(entity["@type"], str) else entity["@type"]):
            if not any(":" in x for x in node.get("@type", [])):
                problems.append("entity %s: type %s does not expand to an IRI" % (entity["@id"], t))

    def refs(value):
        items = value if isinstance(value, list) else [value]
        return [i["@id"] for i in items if isinstance(i, dict) and "@id" in i]

    for entity in graph:
        for key, value in entity.items():
            if key.startswith("@"):
                continue
            for ref in refs(value):
                if ref.startswith("http://") or ref.startswith("https://"):
                    continue
                if ref not in by_id:
                    problems.append("entity %s: %s names %s, which the graph lacks" % (entity["@id"], key, ref))

    root = by_id.get("./")
    if root is None:
        print("no root data entity")
        return 1
    # RO-Crate 1.1 requires a license on the root data entity (ro-crate-js: "licenseRequired"),
    # an entity of the graph or a URI, the entity named.
    licences = refs(root.get("license", [])) if isinstance(root.get("license"), (dict, list)) else \
        ([root["license"]] if isinstance(root.get("license"), str) and root["license"] else [])
    if not licences:
        problems.append("the root has no license, which RO-Crate 1.1 requires (licenseRequired)")
    for lic in licences:
        if not (lic.startswith("http://") or lic.startswith("https://")) and lic not in by_id:
            problems.append("the root's license %s is not an entity of the graph" % lic)
        elif lic in by_id and not by_id[lic].get("name"):
            problems.append("the licence entity %s has no name" % lic)
    profiles = set(refs(root.get("conformsTo", [])))
    for p in ("https://w3id.org/ro/wfrun/process/0.5", "https://w3id.org/ro/wfrun/workflow/0.5",
              "https://w3id.org/ro/wfrun/provenance/0.5"):
        if p not in profiles:
            problems.append("the root does not conform to " + p)
    main_entity = by_id.get(refs(root.get("mainEntity", {}))[0]) if refs(root.get("mainEntity", {})) else None
    if not main_entity or not {"File", "ComputationalWorkflow"} <= set(main_entity["@type"]):
        problems.append("the main entity is not a File typed ComputationalWorkflow")

    # Every payload file, with the size and SHA-256 computed here.
    has_part = set(refs(root.get("hasPart", [])))
    files = 0
    data = os.path.join(bag, "data")
    for folder, _, names in os.walk(data):
        for name in names:
            path = os.path.relpath(os.path.join(folder, name), data).replace(os.sep, "/")
            if path == "ro-crate-metadata.json":
                continue
            files += 1
            entity = by_id.get(path)
            if entity is None:
                problems.append("payload file %s has no File entity" % path)
                continue
            if path not in has_part:
                problems.append("payload file %s is not in the root's hasPart" % path)
            if "File" not in entity["@type"]:
                problems.append("%s is not typed File" % path)
            with open(os.path.join(data, path), "rb") as f:
                content = f.read()
            if "contentSize" in entity and entity["contentSize"] != str(len(content)):
                problems.append("%s: contentSize %s, the file has %d bytes" % (path, entity["contentSize"], len(content)))
            if "sha256" in entity and entity["sha256"] != hashlib.sha256(content).hexdigest():
                problems.append("%s: sha256 differs from the file's" % path)
            if path != "finished-files/report.html" and path != "assembly-files/carrier.xml" and \
                    ("sha256" not in entity or "contentSize" not in entity):
                problems.append("%s: no contentSize or sha256" % path)

    # Every step of the carrier, read here.
    carrier = ET.parse(os.path.join(data, "assembly-files", "carrier.xml")).getroot()
    steps = carrier.findall("%sprocess/%sstep" % (CARRIER, CARRIER))
    ran = {r.get("step") for r in carrier.findall("%sdata/%sresult" % (CARRIER, CARRIER))}
    workflow_steps = refs(main_entity.get("step", [])) if main_entity else []
    for position, step in enumerate(steps, 1):
        sid = step.get("id")
        how = by_id.get("#step-" + sid)
        if how is None or how["@type"] != "HowToStep" or "#step-" + sid not in workflow_steps:
            problems.append("step %s is not a HowToStep of the workflow" % sid)
        elif how.get("position") != str(position):
            problems.append("step %s: position %s, it is step %d" % (sid, how.get("position"), position))
        if sid not in ran:
            continue
        action = by_id.get("#execution-" + sid)
        if action is None or action["@type"] != "CreateAction":
            problems.append("step %s ran but has no CreateAction" % sid)
            continue
        tool = by_id.get(refs(action.get("instrument", {}))[0]) if refs(action.get("instrument", {})) else None
        if not tool or tool["@type"] != "SoftwareApplication" or tool.get("softwareVersion") != step.get("version"):
            problems.append("step %s: its instrument is not the %s stage version %s" % (sid, step.get("component"), step.get("version")))
        for needed in ("startTime", "endTime", "actionStatus"):
            if needed not in action:
                problems.append("step %s: the CreateAction has no %s" % (sid, needed))
        control = by_id.get("#control-" + sid)
        if not control or refs(control.get("object", {})) != ["#execution-" + sid] or \
                refs(control.get("instrument", {})) != ["#step-" + sid]:
            problems.append("step %s: no ControlAction linking its HowToStep and CreateAction" % sid)
        params = step.findall(CARRIER + "param")
        values = [by_id[r] for r in refs(action.get("object", [])) if r in by_id and by_id[r]["@type"] == "PropertyValue"]
        if [(p.get("name"), p.get("value")) for p in params] != [(v.get("name"), v.get("value")) for v in values]:
            problems.append("step %s: its parameters are not the carrier's" % sid)

    for p in problems:
        print(p)
    if problems:
        return 1
    print("ok: %d entities, %d payload files, %d steps (%d ran)" % (len(graph), files, len(steps), len(ran)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
