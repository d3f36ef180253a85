#!/usr/bin/env python3
"""A package's metadata/mets.xml as Archivematica's METS reader, metsrw, reads it.

Makes a capture with the generator, runs it (rights, licence, web copy) and packs it with
the programs under test, then parses mets.xml with metsrw (tests/third_party/metsrw, kept
unmodified) and checks, against the payload files themselves (hashed here with hashlib) and
the bag's manifests:
  - every payload file is one Item of the physical structMap, under Directory divs whose
    labels spell its path, and nothing else is;
  - each has its own amdSec (the file's ADMID) with one PREMIS file object whose path
    identifier, SHA-256, SHA-512 and size are the file's, with a format name;
  - the top Directory (data/) carries the package's amdSec: the intellectual entity (with
    the package and capture identifiers of bag-info.txt, the package's also the METS OBJID),
    the rights statements, every event and every agent; each event an object links to is there,
    and each agent an event links to;
  - GROUPID ties a derivative to the file it was made from (metsrw's derived_from): each
    JPEG export to its original, each web copy file to its model.

usage: metsrw_reads_package.py SURROGATE GENERATOR WORKDIR
Exit 0 when every check passes; otherwise each failure is printed and the exit is 1.
"""
import hashlib
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "third_party", "metsrw"))

import metsrw  # noqa: E402
from metsrw.plugins.premisrw import data_find_all, data_find_text  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


def text(node, path):
    return data_find_text(node.data if hasattr(node, "data") else node, path)


def every(node, path):
    return data_find_all(node.data if hasattr(node, "data") else node, path)


def run(*args):
    result = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        sys.exit(f"{' '.join(args)} failed ({result.returncode}):\n{result.stdout}")


def manifest(bag, algorithm):
    out = {}
    with open(os.path.join(bag, f"manifest-{algorithm}.txt"), encoding="utf-8") as f:
        for line in f:
            digest, path = line.rstrip("\n").split(" ", 1)
            out[path.strip()] = digest
    return out


def main():
    surrogate, generator, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    capture = os.path.join(work, "capture")
    run(generator, "--out", capture, "--images", "6", "--width", "320", "--height", "240",
        "--sphere-radius", "36", "--seed", "11")
    shutil.rmtree(os.path.join(capture, "truth"))
    run(surrogate, "run", capture, "--title", "Stela 12", "--creator", "Ana Silva:photographer",
        "--rights", "research use only", "--license", "https://creativecommons.org/licenses/by/4.0/",
        "--publish", "--quiet")
    bag = os.path.join(work, "stela12")
    run(surrogate, "pack", capture, "-o", bag, "--quiet")

    # The payload as it is on disk, and as the manifests say.
    on_disk = {}
    for folder, _, names in os.walk(os.path.join(bag, "data")):
        for name in names:
            full = os.path.join(folder, name)
            with open(full, "rb") as f:
                content = f.read()
            on_disk[os.path.relpath(full, bag).replace(os.sep, "/")] = (
                len(content), hashlib.sha256(content).hexdigest(), hashlib.sha512(content).hexdigest())
    sha256, sha512 = manifest(bag, "sha256"), manifest(bag, "sha512")
    check(set(sha256) == set(on_disk) == set(sha512), "the manifests do not list the payload on disk")
    check(any(p.startswith("data/finished-files/web/") for p in on_disk), "the capture has no web copy")

    # metsrw refuses a CREATEDATE "more recent than now" by comparing it as text with now in
    # microseconds: "...T10:00:00Z" is later than "...T10:00:00.5" (Z sorts after "."), so a
    # METS is refused within the second it was written. A repository reads it later.
    time.sleep(1.1)
    mets = metsrw.METSDocument.fromfile(os.path.join(bag, "metadata", "mets.xml"))
    entries = mets.all_files()
    items = {e.path: e for e in entries if e.type == "Item"}
    check(len(items) == len([e for e in entries if e.type == "Item"]), "two Items have the same path")
    check(set(items) == set(on_disk),
          f"metsrw reads {len(items)} files; the payload has {len(on_disk)}: missing "
          f"{sorted(set(on_disk) - set(items))[:5]}, extra {sorted(set(items) - set(on_disk))[:5]}")

    roots = [e for e in entries if e.parent is None]
    if not check(len(roots) == 1 and roots[0].type == "Directory" and roots[0].label == "data",
                 f"the structMap's top div is not one Directory 'data': {roots}"):
        return report(items, {}, set(), set())
    root = roots[0]

    # The package-level metadata on the data/ Directory.
    events = {text(e, "event_identifier/event_identifier_value"): e for e in root.get_premis_events()}
    agents = {(text(a, "agent_identifier/agent_identifier_type"), text(a, "agent_identifier/agent_identifier_value"))
              for a in root.get_premis_agents()}
    rights = root.get_premis_rights()
    statements = {text(s, "rights_statement_identifier/rights_statement_identifier_value")
                  for r in rights for s in every(r, "rights_statement")}
    entity = root.get_premis_objects()
    check("event-capture" in events and "event-packaging" in events and "event-message-digest" in events,
          f"the package's events are not all on the data/ Directory: {sorted(events)}")
    check(len(entity) == 1 and entity[0].attributes.get("xsi:type") == "premis:intellectualEntity",
          "the data/ Directory has no intellectual entity")
    # The identifiers of bag-info.txt are the METS document's and the entity's.
    info = {}
    with open(os.path.join(bag, "bag-info.txt"), encoding="utf-8") as f:
        for line in f:
            label, _, value = line.rstrip("\n").partition(": ")
            info.setdefault(label, value)
    check(info.get("Surrogate-Package-Identifier", "").startswith("urn:sha256:") and
          info.get("Surrogate-Capture-Identifier", "").startswith("urn:surrogate:capture:"),
          "bag-info.txt does not name the package and the capture")
    check(mets.objid == info.get("Surrogate-Package-Identifier"), f"OBJID {mets.objid} is not the package identifier")
    entity_ids = {(text(i, "object_identifier_type"), text(i, "object_identifier_value"))
                  for e in entity for i in every(e, "object_identifier")}
    for kind, label in (("package", "Surrogate-Package-Identifier"), ("capture", "Surrogate-Capture-Identifier")):
        check((f"Surrogate {kind} identifier", info.get(label)) in entity_ids,
              f"the intellectual entity has no {kind} identifier {info.get(label)}: {sorted(entity_ids)}")
    check(any(a.text == info.get("Surrogate-Capture-Identifier") for a in mets.alternate_ids),
          "no altRecordID holds the capture identifier")
    check(statements == {"rights-license", "rights-statement"}, f"rights statements: {sorted(statements)}")
    check(sorted(d.contents.mdtype for d in root.dmdsecs) == ["DC", "OTHER"],
          "the data/ Directory does not point at the Dublin Core and the CRM description")
    for ev_id, ev in events.items():
        check(text(ev, "event_type") != "", f"event {ev_id} has no type")
        for link in every(ev, "linking_agent_identifier"):
            key = (text(link, "linking_agent_identifier_type"), text(link, "linking_agent_identifier_value"))
            check(key in agents, f"event {ev_id} links agent {key}, which metsrw did not read")
    for link in every(entity[0], "linking_rights_statement_identifier") if entity else []:
        value = text(link, "linking_rights_statement_identifier_value")
        check(value in statements, f"the intellectual entity links rights statement {value}, which is not there")

    for path, item in sorted(items.items()):
        size, digest256, digest512 = on_disk.get(path, (None, None, None))
        # The Directory labels above it, and its own, spell its path.
        labels, e = [], item
        while e is not None:
            labels.insert(0, e.label)
            e = e.parent
        check("/".join(labels) == path, f"{path}: the structMap places it at {'/'.join(labels)}")
        check(all(a.type == "Directory" for a in _ancestors(item)), f"{path}: a div above it is not a Directory")
        check(item.checksumtype == "SHA-256" and item.checksum == digest256, f"{path}: METS CHECKSUM is not its SHA-256")
        check(len(item.amdsecs) == 1, f"{path}: {len(item.amdsecs)} amdSecs, not its own one")
        objects = item.get_premis_objects()
        if not check(len(objects) == 1, f"{path}: {len(objects)} PREMIS objects in its amdSec"):
            continue
        o = objects[0]
        check(o.attributes.get("xsi:type") == "premis:file", f"{path}: its object is not a premis:file")
        ids = {(text(i, "object_identifier_type"), text(i, "object_identifier_value")) for i in every(o, "object_identifier")}
        check(("BagIt payload path", path) in ids, f"{path}: its object is identified as {sorted(ids)}")
        fixity = {text(f, "message_digest_algorithm"): text(f, "message_digest")
                  for f in every(o, "object_characteristics/fixity")}
        check(fixity.get("SHA-256") == digest256 == sha256.get(path), f"{path}: SHA-256 {fixity.get('SHA-256')}")
        check(fixity.get("SHA-512") == digest512 == sha512.get(path), f"{path}: SHA-512 {fixity.get('SHA-512')}")
        check(text(o, "object_characteristics/size") == str(size), f"{path}: size {text(o, 'object_characteristics/size')}")
        check(text(o, "object_characteristics/format/format_designation/format_name") != "", f"{path}: no format name")
        linked = [text(link, "linking_event_identifier_value") for link in every(o, "linking_event_identifier")]
        check(bool(linked), f"{path}: its object links no event")
        for ev_id in linked:
            check(ev_id in events, f"{path}: links event {ev_id}, which metsrw did not read")
        # Derivatives made from one file share its group.
        if path.startswith("data/jpeg-exports/"):
            source = item.derived_from.path if item.derived_from else None
            stem = os.path.splitext(os.path.basename(path))[0]
            check(source is not None and source.startswith("data/original-captures/" + stem + "."),
                  f"{path}: derived from {source}, not its original")
        elif path == "data/finished-files/web/index.html":
            # The index of every model is a version of none of them.
            check(item.derived_from is None, f"{path}: the index of the models, read as derived from {item.derived_from}")
        elif path.startswith("data/finished-files/web/"):
            model = path.split("/")[3]
            source = item.derived_from.path if item.derived_from else None
            check(source is not None and os.path.splitext(os.path.basename(source))[0] == model,
                  f"{path}: derived from {source}, not the model {model}")
        elif path.startswith("data/original-captures/"):
            check(item.derived_from is None, f"{path}: an original, read as derived from {item.derived_from}")

    return report(items, events, agents, statements)


def report(items, events, agents, statements):
    for failure in failures:
        print("FAIL:", failure)
    print(f"metsrw {metsrw.__version__} read {len(items)} payload files, {len(events)} events, "
          f"{len(agents)} agents, {len(statements)} rights statements; {len(failures)} failures")
    return 1 if failures else 0


def _ancestors(entry):
    e = entry.parent
    while e is not None:
        yield e
        e = e.parent


if __name__ == "__main__":
    sys.exit(main())
