#!/usr/bin/python3
"""Runs the CSIP 2.1.0 schematron rules of the E-ARK validator on a METS file, offline.

The rule files (tests/third_party/eark-validator/schematron-csip-2.1.0) hold placeholders for
tests the validator builds when it starts: "@TYPE_vocabulary_test" and the like become "(@TYPE =
'term1') or (@TYPE = 'term2') ..." from the DILCIS vocabularies, which the validator downloads;
here they come from the copies kept beside the rules (vocabs/), and "@MIMETYPE_IANA_test" from
its IANA.txt, as eark_validator/ipxml/schematron.py does. Each rule file is then compiled by
lxml's ISO schematron and run on the METS. Prints every failed assertion of role ERROR (and,
with --all, WARN), one a line "ID: text"; exit 0 when there is none, 1 otherwise.

Usage: csip_schematron.py [--all] METS.xml
"""
import os
import sys

from lxml import etree
from lxml.isoschematron import Schematron

HERE = os.path.dirname(os.path.abspath(__file__))
RULES = os.path.join(HERE, "..", "..", "third_party", "eark-validator")
VOCABULARIES = {
    "@TYPE": "CSIPVocabularyContentCategory.xml",
    "@csip:CONTENTINFORMATIONTYPE": "CSIPVocabularyContentInformationType.xml",
    "@csip:OAISPACKAGETYPE": "CSIPVocabularyOAISPackageType.xml",
    "@STATUS": "CSIPVocabularyStatus.xml",
}
SVRL = "{http://purl.oclc.org/dsdl/svrl}"


def terms(file_name):
    tree = etree.parse(os.path.join(RULES, "vocabs", file_name))
    return [t.text for t in tree.iter() if isinstance(t.tag, str) and t.tag.endswith("Term") and t.text]


def substitutions():
    tests = {}
    for attribute, file_name in VOCABULARIES.items():
        tests[attribute + "_vocabulary_test"] = " or ".join(
            "({} = '{}')".format(attribute, term) for term in terms(file_name))
    with open(os.path.join(RULES, "vocabs", "IANA.txt"), encoding="utf-8") as iana:
        tests["@MIMETYPE_IANA_test"] = " or ".join(
            "(@MIMETYPE = '{}')".format(line.rstrip("\n")) for line in iana if line.strip())
    return tests


def main():
    args = sys.argv[1:]
    roles = {"ERROR"}
    if args and args[0] == "--all":
        roles.add("WARN")
        args = args[1:]
    if len(args) != 1:
        print(__doc__)
        return 2
    document = etree.parse(args[0])
    tests = substitutions()
    folder = os.path.join(RULES, "schematron-csip-2.1.0")
    failures = 0
    for name in sorted(os.listdir(folder)):
        with open(os.path.join(folder, name), encoding="utf-8") as f:
            text = f.read()
        for placeholder, test in tests.items():
            text = text.replace(placeholder, test)
        rules = Schematron(etree.XML(text.encode("utf-8")), store_report=True)
        rules.validate(document)
        for failed in rules.validation_report.iter(SVRL + "failed-assert"):
            if failed.get("role") not in roles:
                continue
            text_element = failed.find(SVRL + "text")
            print("{}: {} ({}; {})".format(failed.get("id"), " ".join((text_element.text or "").split())[:160],
                                           failed.get("location"), name))
            failures += 1
    print("{} rule files, {} failed assertions".format(len(os.listdir(folder)), failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
