<?xml version="1.0" encoding="UTF-8"?>
<!--
  Surrogate carrier -> METS 1.12.1 with PREMIS 3 (metadata/mets.xml of a Surrogate package).

  Input: a carrier (namespace urn:surrogate:carrier:1, schema xsd/carrier.xsd).
  Parameters (package facts the carrier cannot hold; Surrogate records them in bag-info.txt):
    package-id      the package identifier (bag-info Surrogate-Package-Identifier)
    packaging-time  xs:dateTime of packaging (bag-info Surrogate-Packaging-Time)
    software-agent  the packing software, e.g. "Surrogate 0.1.0" (bag-info Bag-Software-Agent)
    previous-package-id  the package an earlier pack of this capture made, before its record
                    last changed (bag-info Surrogate-Previous-Package-Identifier); empty: none
    payload-uri     URI of a payload list, one element per payload file of the bag:
                      <payload><file path="data/..." size="N" sha256="hex" sha512="hex"/></payload>
                    (Surrogate builds it from manifest-sha256.txt and manifest-sha512.txt;
                    it leaves out size and sha256 where the carrier's record of the same path,
                    data/ + @path, gives the same ones, and they are taken from there; and it
                    names each element after the file's group, the role of that record or
                    "other" when there is none: <original .../>, <result .../>; a result in
                    finished-files/web/ (the web copy) is <access .../>. A <file>'s
                    group is looked up here). When
                    the list has no file, the carrier's own file list is used instead (without
                    SHA-512). Give an absolute path or URI: a relative one is resolved against
                    this stylesheet's location.
  What it holds: Dublin Core (dmdSec dmd-dc) beside a pointer to crm.rdf; in the package's
  amdSec (amd) the capture as a PREMIS intellectual entity, the rights statements (rightsMD),
  one event per capture, command run, pipeline step and packaging act (eventType from the
  Library of Congress vocabulary id.loc.gov/vocabulary/preservation/eventType), and each agent
  once; in an amdSec per payload file its PREMIS file object (fixity, size, format with the PRONOM
  identifier the carrier records, derivation relationships to what the step that made it used); the
  fileSec by role; a physical structMap of Directory and Item divs, the layout Archivematica's
  METS reader (metsrw) walks.
  The mapping is explained, element by element, in mappings/carrier-to-mets.md.
  Re-derive by hand:
    xsltproc -\-stringparam package-id ID -\-stringparam packaging-time T \
             -\-stringparam software-agent "Surrogate X" -\-stringparam payload-uri payload.xml \
             carrier-to-mets.xsl data/assembly-files/carrier.xml
  Output is deterministic: the same carrier and parameters give the same bytes.
-->
<xsl:stylesheet version="1.0"
    xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:c="urn:surrogate:carrier:1"
    xmlns:mets="http://www.loc.gov/METS/"
    xmlns:premis="http://www.loc.gov/premis/v3"
    xmlns:xlink="http://www.w3.org/1999/xlink"
    xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
    xmlns:dc="http://purl.org/dc/elements/1.1/"
    exclude-result-prefixes="c">

  <xsl:output method="xml" encoding="UTF-8" indent="yes"/>
  <!-- White space between the carrier's elements is layout, never data (Surrogate parses the
       carrier without it, to keep the tree small; this makes xsltproc read it the same way). -->
  <xsl:strip-space elements="*"/>

  <xsl:param name="package-id" select="''"/>
  <xsl:param name="packaging-time" select="''"/>
  <xsl:param name="software-agent" select="'Surrogate'"/>
  <xsl:param name="previous-package-id" select="''"/>
  <xsl:param name="payload-uri" select="''"/>
  <!-- The edition of these rules (src/mapping/mapping.h, kMappingEdition): 1 for packages made
       before JSON and JavaScript files (data/ro-crate-metadata.json among them) had their formats. -->
  <xsl:param name="mapping-edition" select="2"/>

  <xsl:variable name="carrier" select="/c:carrier"/>
  <xsl:variable name="payload" select="document($payload-uri)/payload/*"/>
  <xsl:variable name="objid">
    <xsl:choose>
      <xsl:when test="$package-id != ''"><xsl:value-of select="$package-id"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="concat('urn:sha256:', $carrier/c:files/c:file[1]/@sha256)"/></xsl:otherwise>
    </xsl:choose>
  </xsl:variable>
  <!-- The capture identifier: the same string in crm.rdf (carrier-to-crm.xsl) and bag-info.txt
       (Surrogate-Capture-Identifier); the first file is the first photograph, which no run
       changes, so every package of the capture has it. -->
  <xsl:variable name="capture-id">
    <xsl:choose>
      <xsl:when test="$carrier/c:files/c:file"><xsl:value-of select="concat('urn:surrogate:capture:', $carrier/c:files/c:file[1]/@sha256)"/></xsl:when>
      <xsl:otherwise>urn:surrogate:capture:unidentified</xsl:otherwise>
    </xsl:choose>
  </xsl:variable>
  <xsl:variable name="pack-time">
    <xsl:choose>
      <xsl:when test="$packaging-time != ''"><xsl:value-of select="$packaging-time"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="$carrier/c:header/c:modified"/></xsl:otherwise>
    </xsl:choose>
  </xsl:variable>
  <xsl:variable name="surrogate" select="$carrier/c:header/c:software[@name = 'Surrogate'][1]"/>
  <!-- The carrier's own path in the bag: the record every command run rewrote. -->
  <xsl:variable name="carrier-path" select="'data/assembly-files/carrier.xml'"/>
  <!-- The run that made the record's current state: the last completed run (a failed run after
       it left that state in place); with no completed run, the last run. -->
  <xsl:variable name="state-run">
    <xsl:choose>
      <xsl:when test="$carrier/c:header/c:run[@outcome = 'completed']"><xsl:value-of select="$carrier/c:header/c:run[@outcome = 'completed'][last()]/@id"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="$carrier/c:header/c:run[last()]/@id"/></xsl:otherwise>
    </xsl:choose>
  </xsl:variable>

  <!-- Persons: creators, people who ran commands, intervened or logged; grouped by name
       (Muenchian). -->
  <xsl:key name="person" match="c:creator" use="normalize-space(.)"/>
  <xsl:key name="person" match="c:run/@who | c:intervention/@who | c:entry/@who" use="normalize-space(.)"/>
  <xsl:key name="camera" match="c:file[@role = 'original']/c:camera"
           use="concat(@make, '|', @model, '|', @serial)"/>
  <!-- The carrier's file records by payload path ("data/" + path) and by id. They are looked up
       once or more per payload file: a search of the whole list each time made deriving the
       METS of a package of many files quadratic. key() looks in the document of the context
       node, hence the for-each over $carrier (one node) around each lookup from the payload. -->
  <xsl:key name="file-by-bag-path" match="c:files/c:file" use="concat('data/', @path)"/>
  <xsl:key name="file-by-id" match="c:files/c:file" use="@id"/>
  <xsl:key name="evidence-by-path" match="c:header/c:audited/c:evidence" use="@path"/>
  <xsl:key name="step-by-id" match="c:process/c:step" use="@id"/>
  <xsl:key name="file-by-creator" match="c:files/c:file" use="@createdBy"/>
  <xsl:key name="result-by-step" match="c:data/c:result" use="@step"/>
  <!-- What a step's results name as used (an input file, or an image a per-image result is
       about), keyed by "step-id file-id", and the images ImageDecode decoded: sources are
       selected by testing each file against these keys, which stays linear in the number of
       files (key() given a node-set of N values merges N node-sets, quadratic in libxslt). -->
  <xsl:key name="step-input" match="c:data/c:result/c:input/@file | c:data/c:result/*/@image" use="concat(../../@step, ' ', .)"/>
  <xsl:key name="decoded-image" match="c:data/c:result/c:decoded/@image" use="."/>
  <!-- Pipeline stages by component and version: one PREMIS agent each. -->
  <xsl:key name="stage" match="c:process/c:step" use="concat(@component, ' ', @version)"/>
  <!-- The folders each payload file is in, as paths relative to data/ ending in "/" (a file
       data/finished-files/web/hsh2/info.json is in "finished-files/", "finished-files/web/" and
       "finished-files/web/hsh2/"): the structMap's Directory divs. One declaration per depth,
       down to $folder-depth folders below data/ (Surrogate writes five at most:
       finished-files/web/MODEL/plane_N_files/LEVEL/), for the payload list and for the
       carrier's files (used without one). XPath 1.0 cannot find the last "/" of a path, so
       each depth cuts its own number of leading segments. -->
  <xsl:key name="in-folder" match="payload/*[contains(substring-after(@path, '/'), '/')]"
           use="substring(@path, 6, string-length(@path) - 5 - string-length(substring-after(substring-after(@path, '/'), '/')))"/>
  <xsl:key name="in-folder" match="payload/*[contains(substring-after(substring-after(@path, '/'), '/'), '/')]"
           use="substring(@path, 6, string-length(@path) - 5 - string-length(substring-after(substring-after(substring-after(@path, '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="payload/*[contains(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/')]"
           use="substring(@path, 6, string-length(@path) - 5 - string-length(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="payload/*[contains(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 6, string-length(@path) - 5 - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="payload/*[contains(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 6, string-length(@path) - 5 - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="payload/*[contains(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 6, string-length(@path) - 5 - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="payload/*[contains(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 6, string-length(@path) - 5 - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="payload/*[contains(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 6, string-length(@path) - 5 - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="c:files/c:file[contains(@path, '/')]"
           use="substring(@path, 1, string-length(@path) - string-length(substring-after(@path, '/')))"/>
  <xsl:key name="in-folder" match="c:files/c:file[contains(substring-after(@path, '/'), '/')]"
           use="substring(@path, 1, string-length(@path) - string-length(substring-after(substring-after(@path, '/'), '/')))"/>
  <xsl:key name="in-folder" match="c:files/c:file[contains(substring-after(substring-after(@path, '/'), '/'), '/')]"
           use="substring(@path, 1, string-length(@path) - string-length(substring-after(substring-after(substring-after(@path, '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="c:files/c:file[contains(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/')]"
           use="substring(@path, 1, string-length(@path) - string-length(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="c:files/c:file[contains(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 1, string-length(@path) - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="c:files/c:file[contains(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 1, string-length(@path) - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="c:files/c:file[contains(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 1, string-length(@path) - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:key name="in-folder" match="c:files/c:file[contains(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/'), '/')]"
           use="substring(@path, 1, string-length(@path) - string-length(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(substring-after(@path, '/'), '/'), '/'), '/'), '/'), '/'), '/'), '/')))"/>
  <xsl:variable name="event-types" select="'http://id.loc.gov/vocabulary/preservation/eventType'"/>
  <!-- How deep the structMap nests folders below data/ (the in-folder keys above): a file in a
       deeper folder is an Item of the deepest one, labelled with the rest of its path. -->
  <xsl:variable name="folder-depth" select="8"/>
  <!-- The person who ran the command that made the record's current state: the operator of
       its steps (none in carriers written before runs were recorded). -->
  <xsl:variable name="operator" select="normalize-space($carrier/c:header/c:run[@id = $state-run]/@who)"/>
  <!-- Whether the packer is the Surrogate the header names (then it is that one agent). -->
  <xsl:variable name="packer-is-surrogate" select="$surrogate and $software-agent = concat($surrogate/@name, ' ', $surrogate/@version)"/>

  <xsl:template match="/">
    <xsl:apply-templates select="c:carrier"/>
  </xsl:template>

  <xsl:template match="c:carrier">
    <mets:mets OBJID="{$objid}" LABEL="{c:header/c:title}" TYPE="RTI capture"
               PROFILE="urn:surrogate:package:1"
               xsi:schemaLocation="http://www.loc.gov/METS/ http://www.loc.gov/standards/mets/version1121/mets.xsd http://www.loc.gov/premis/v3 http://www.loc.gov/standards/premis/v3/premis.xsd">
      <mets:metsHdr CREATEDATE="{$pack-time}" RECORDSTATUS="complete">
        <mets:agent ROLE="CREATOR" TYPE="OTHER" OTHERTYPE="SOFTWARE">
          <mets:name><xsl:value-of select="$software-agent"/></mets:name>
          <mets:note>METS and PREMIS derived from the carrier by xslt/carrier-to-mets.xsl</mets:note>
        </mets:agent>
        <xsl:for-each select="c:header/c:creator">
          <mets:agent ROLE="OTHER" OTHERROLE="{@role}" TYPE="INDIVIDUAL">
            <mets:name><xsl:value-of select="normalize-space(.)"/></mets:name>
          </mets:agent>
        </xsl:for-each>
        <xsl:for-each select="c:header/c:meta[@key = 'Source-Organization']">
          <mets:agent ROLE="IPOWNER" TYPE="ORGANIZATION">
            <mets:name><xsl:value-of select="."/></mets:name>
          </mets:agent>
        </xsl:for-each>
        <xsl:for-each select="c:header/c:meta[@key = 'External-Identifier']">
          <mets:altRecordID TYPE="External-Identifier"><xsl:value-of select="."/></mets:altRecordID>
        </xsl:for-each>
        <mets:altRecordID TYPE="Surrogate capture identifier"><xsl:value-of select="$capture-id"/></mets:altRecordID>
      </mets:metsHdr>

      <xsl:call-template name="dublin-core"/>
      <mets:dmdSec ID="dmd-crm">
        <mets:mdRef LOCTYPE="URL" xlink:href="crm.rdf" MDTYPE="OTHER"
                    OTHERMDTYPE="CIDOC-CRM+CRMdig" MIMETYPE="application/rdf+xml"
                    LABEL="CIDOC-CRM description of the object, the capture and its processing"/>
      </mets:dmdSec>

      <!-- What is about the whole package (the capture as an intellectual entity, its rights,
           every event and agent), in one amdSec that the structMap's top div, the data/
           folder, points at; then one amdSec per payload file, which its METS file points at
           (ADMID), holding its PREMIS object: the layout Archivematica's METS reader (metsrw)
           walks. Events and agents are not repeated in each file's amdSec: the capture event
           alone names every photograph, and a copy of it for each would grow with the square
           of their number. -->
      <mets:amdSec ID="amd">
        <xsl:call-template name="intellectual-entity"/>
        <xsl:call-template name="rights"/>
        <xsl:call-template name="events"/>
        <xsl:call-template name="agents"/>
      </mets:amdSec>
      <xsl:call-template name="objects"/>

      <mets:fileSec ID="fileSec">
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'original'"/></xsl:call-template>
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'export'"/></xsl:call-template>
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'lp'"/></xsl:call-template>
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'sidecar'"/></xsl:call-template>
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'assembly'"/></xsl:call-template>
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'result'"/></xsl:call-template>
        <!-- the web copy (surrogate run with publish): results in finished-files/web/, the access copy -->
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'access'"/></xsl:call-template>
        <!-- files another tool made (RTIBuilder's .lp, log, .ptm), found in the output folders -->
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'prior'"/><xsl:with-param name="label" select="'prior-work'"/></xsl:call-template>
        <xsl:call-template name="file-group"><xsl:with-param name="use" select="'other'"/></xsl:call-template>
      </mets:fileSec>

      <!-- The bag's payload as folders and files (Archivematica's convention: TYPE "Directory"
           and "Item", LABEL the name), in path order; the file groups say what each file is. -->
      <mets:structMap ID="structMap-physical" TYPE="physical" LABEL="Package layout">
        <mets:div TYPE="Directory" LABEL="data" DMDID="dmd-dc dmd-crm" ADMID="amd">
          <xsl:choose>
            <xsl:when test="$use-payload">
              <xsl:call-template name="folder">
                <xsl:with-param name="members" select="$payload"/>
                <xsl:with-param name="skip" select="5"/>
              </xsl:call-template>
            </xsl:when>
            <xsl:otherwise>
              <xsl:call-template name="folder">
                <xsl:with-param name="members" select="c:files/c:file"/>
                <xsl:with-param name="skip" select="0"/>
              </xsl:call-template>
            </xsl:otherwise>
          </xsl:choose>
        </mets:div>
      </mets:structMap>
    </mets:mets>
  </xsl:template>

  <!-- Descriptive metadata: Dublin Core (simple, the 15 elements of
       http://purl.org/dc/elements/1.1/) from the carrier's header. Which header field and which
       meta keys give which element: mappings/carrier-to-mets.md, "Dublin Core". -->
  <!-- One dc:format per media type, in the order of each type's first file. One pass over the
       files per type found (a handful): grouping by key() would copy the node-set of every
       file of a type for every file, quadratic in libxslt (minutes at 100 000 files). -->
  <xsl:template name="dc-formats">
    <xsl:param name="seen" select="'|'"/>
    <xsl:variable name="next" select="(c:files/c:file[@mediaType != ''][not(contains($seen, concat('|', @mediaType, '|')))])[1]"/>
    <xsl:if test="$next">
      <dc:format><xsl:value-of select="$next/@mediaType"/></dc:format>
      <xsl:call-template name="dc-formats">
        <xsl:with-param name="seen" select="concat($seen, $next/@mediaType, '|')"/>
      </xsl:call-template>
    </xsl:if>
  </xsl:template>

  <xsl:template name="dublin-core">
    <xsl:variable name="h" select="c:header"/>
    <xsl:variable name="shot">
      <xsl:for-each select="c:files/c:file[@role = 'original']/c:camera/@dateTimeOriginal">
        <xsl:sort select="."/>
        <xsl:if test="position() = 1"><xsl:call-template name="exif-date"><xsl:with-param name="d" select="."/></xsl:call-template></xsl:if>
      </xsl:for-each>
    </xsl:variable>
    <mets:dmdSec ID="dmd-dc">
      <mets:mdWrap MDTYPE="DC" MIMETYPE="text/xml" LABEL="Dublin Core description of the capture">
        <mets:xmlData>
          <dc:title><xsl:value-of select="$h/c:title"/></dc:title>
          <xsl:for-each select="$h/c:creator">
            <dc:creator><xsl:value-of select="normalize-space(.)"/></dc:creator>
          </xsl:for-each>
          <xsl:for-each select="$h/c:meta[@key = 'Subject']">
            <dc:subject><xsl:value-of select="."/></dc:subject>
          </xsl:for-each>
          <xsl:for-each select="$h/c:meta[@key = 'Description' or @key = 'External-Description']">
            <dc:description><xsl:value-of select="."/></dc:description>
          </xsl:for-each>
          <dc:description><xsl:value-of select="concat('Highlight-RTI capture of ', count(c:files/c:file[@role = 'original']), ' images, with the files derived from them by Surrogate')"/></dc:description>
          <xsl:for-each select="$h/c:meta[@key = 'Publisher' or @key = 'Source-Organization']">
            <dc:publisher><xsl:value-of select="."/></dc:publisher>
          </xsl:for-each>
          <xsl:for-each select="$h/c:meta[@key = 'Contributor']">
            <dc:contributor><xsl:value-of select="."/></dc:contributor>
          </xsl:for-each>
          <!-- the date of the capture: the first shot's day (camera clock), else the day the
               record was begun -->
          <dc:date>
            <xsl:choose>
              <xsl:when test="$shot != ''"><xsl:value-of select="substring($shot, 1, 10)"/></xsl:when>
              <xsl:otherwise><xsl:value-of select="substring($h/c:created, 1, 10)"/></xsl:otherwise>
            </xsl:choose>
          </dc:date>
          <dc:type>Image</dc:type>
          <xsl:call-template name="dc-formats"/>
          <dc:identifier><xsl:value-of select="$objid"/></dc:identifier>
          <dc:identifier><xsl:value-of select="$capture-id"/></dc:identifier>
          <xsl:for-each select="$h/c:meta[@key = 'External-Identifier' or @key = 'Object-Identifier']">
            <dc:identifier><xsl:value-of select="."/></dc:identifier>
          </xsl:for-each>
          <xsl:for-each select="$h/c:meta[@key = 'Source']">
            <dc:source><xsl:value-of select="."/></dc:source>
          </xsl:for-each>
          <xsl:for-each select="$h/c:meta[@key = 'Language']">
            <dc:language><xsl:value-of select="."/></dc:language>
          </xsl:for-each>
          <xsl:for-each select="$h/c:meta[@key = 'Relation']">
            <dc:relation><xsl:value-of select="."/></dc:relation>
          </xsl:for-each>
          <xsl:for-each select="$h/c:meta[@key = 'Coverage']">
            <dc:coverage><xsl:value-of select="."/></dc:coverage>
          </xsl:for-each>
          <xsl:for-each select="$h/c:rights">
            <dc:rights><xsl:value-of select="."/></dc:rights>
          </xsl:for-each>
          <xsl:for-each select="$h/c:license">
            <dc:rights><xsl:value-of select="."/></dc:rights>
          </xsl:for-each>
        </mets:xmlData>
      </mets:mdWrap>
    </mets:dmdSec>
  </xsl:template>

  <!-- The intellectual entity: the capture, which every file of the package is part of. -->
  <xsl:template name="intellectual-entity">
    <mets:techMD ID="object-ie">
      <mets:mdWrap MDTYPE="PREMIS:OBJECT">
        <mets:xmlData>
          <premis:object xsi:type="premis:intellectualEntity" version="3.0">
            <premis:objectIdentifier>
              <premis:objectIdentifierType>Surrogate package identifier</premis:objectIdentifierType>
              <premis:objectIdentifierValue><xsl:value-of select="$objid"/></premis:objectIdentifierValue>
            </premis:objectIdentifier>
            <premis:objectIdentifier>
              <premis:objectIdentifierType>Surrogate capture identifier</premis:objectIdentifierType>
              <premis:objectIdentifierValue><xsl:value-of select="$capture-id"/></premis:objectIdentifierValue>
            </premis:objectIdentifier>
            <xsl:for-each select="c:header/c:meta[@key = 'External-Identifier' or @key = 'Object-Identifier']">
              <premis:objectIdentifier>
                <premis:objectIdentifierType><xsl:value-of select="@key"/></premis:objectIdentifierType>
                <premis:objectIdentifierValue><xsl:value-of select="."/></premis:objectIdentifierValue>
              </premis:objectIdentifier>
            </xsl:for-each>
            <premis:significantProperties>
              <premis:significantPropertiesType>content</premis:significantPropertiesType>
              <premis:significantPropertiesValue><xsl:value-of select="concat('Highlight-RTI capture of ', c:header/c:title, ': ', count(c:files/c:file[@role = 'original']), ' photographs and the files derived from them')"/></premis:significantPropertiesValue>
            </premis:significantProperties>
            <premis:originalName><xsl:value-of select="c:header/c:title"/></premis:originalName>
            <!-- a revision: the package an earlier pack of this capture made, before its record
                 last changed; this one was made from the capture's newer state by packaging -->
            <xsl:if test="$previous-package-id != ''">
              <premis:relationship>
                <premis:relationshipType>derivation</premis:relationshipType>
                <premis:relationshipSubType>has source</premis:relationshipSubType>
                <premis:relatedObjectIdentifier>
                  <premis:relatedObjectIdentifierType>Surrogate package identifier</premis:relatedObjectIdentifierType>
                  <premis:relatedObjectIdentifierValue><xsl:value-of select="$previous-package-id"/></premis:relatedObjectIdentifierValue>
                </premis:relatedObjectIdentifier>
                <premis:relatedEventIdentifier>
                  <premis:relatedEventIdentifierType>Surrogate event</premis:relatedEventIdentifierType>
                  <premis:relatedEventIdentifierValue>event-packaging</premis:relatedEventIdentifierValue>
                </premis:relatedEventIdentifier>
              </premis:relationship>
            </xsl:if>
            <premis:linkingEventIdentifier>
              <premis:linkingEventIdentifierType>Surrogate event</premis:linkingEventIdentifierType>
              <premis:linkingEventIdentifierValue>event-capture</premis:linkingEventIdentifierValue>
            </premis:linkingEventIdentifier>
            <premis:linkingEventIdentifier>
              <premis:linkingEventIdentifierType>Surrogate event</premis:linkingEventIdentifierType>
              <premis:linkingEventIdentifierValue>event-packaging</premis:linkingEventIdentifierValue>
            </premis:linkingEventIdentifier>
            <xsl:call-template name="linking-rights"/>
          </premis:object>
        </mets:xmlData>
      </mets:mdWrap>
    </mets:techMD>
  </xsl:template>

  <!-- Rights: the licence (option license) and the depositor's statement (option rights) as PREMIS
       rights statements about the capture; with neither, a statement that none was given. -->
  <xsl:template name="linking-rights">
    <xsl:for-each select="$carrier/c:header">
      <xsl:if test="c:license">
        <premis:linkingRightsStatementIdentifier>
          <premis:linkingRightsStatementIdentifierType>Surrogate rights statement</premis:linkingRightsStatementIdentifierType>
          <premis:linkingRightsStatementIdentifierValue>rights-license</premis:linkingRightsStatementIdentifierValue>
        </premis:linkingRightsStatementIdentifier>
      </xsl:if>
      <xsl:if test="c:rights or not(c:license)">
        <premis:linkingRightsStatementIdentifier>
          <premis:linkingRightsStatementIdentifierType>Surrogate rights statement</premis:linkingRightsStatementIdentifierType>
          <premis:linkingRightsStatementIdentifierValue>rights-statement</premis:linkingRightsStatementIdentifierValue>
        </premis:linkingRightsStatementIdentifier>
      </xsl:if>
    </xsl:for-each>
  </xsl:template>

  <xsl:template name="rights-object-link">
    <premis:linkingObjectIdentifier>
      <premis:linkingObjectIdentifierType>Surrogate package identifier</premis:linkingObjectIdentifierType>
      <premis:linkingObjectIdentifierValue><xsl:value-of select="$objid"/></premis:linkingObjectIdentifierValue>
    </premis:linkingObjectIdentifier>
  </xsl:template>

  <xsl:template name="rights">
    <xsl:variable name="h" select="c:header"/>
    <mets:rightsMD ID="rights">
      <mets:mdWrap MDTYPE="PREMIS:RIGHTS">
        <mets:xmlData>
          <premis:rights version="3.0">
            <xsl:if test="$h/c:license">
              <premis:rightsStatement>
                <premis:rightsStatementIdentifier>
                  <premis:rightsStatementIdentifierType>Surrogate rights statement</premis:rightsStatementIdentifierType>
                  <premis:rightsStatementIdentifierValue>rights-license</premis:rightsStatementIdentifierValue>
                </premis:rightsStatementIdentifier>
                <premis:rightsBasis>license</premis:rightsBasis>
                <premis:licenseInformation>
                  <premis:licenseDocumentationIdentifier>
                    <premis:licenseDocumentationIdentifierType>URI</premis:licenseDocumentationIdentifierType>
                    <premis:licenseDocumentationIdentifierValue><xsl:value-of select="$h/c:license"/></premis:licenseDocumentationIdentifierValue>
                    <premis:licenseDocumentationRole>license</premis:licenseDocumentationRole>
                  </premis:licenseDocumentationIdentifier>
                  <premis:licenseNote>the licence the depositor named when recording the capture (surrogate run, option license)</premis:licenseNote>
                </premis:licenseInformation>
                <xsl:call-template name="rights-object-link"/>
              </premis:rightsStatement>
            </xsl:if>
            <xsl:if test="$h/c:rights or not($h/c:license)">
              <premis:rightsStatement>
                <premis:rightsStatementIdentifier>
                  <premis:rightsStatementIdentifierType>Surrogate rights statement</premis:rightsStatementIdentifierType>
                  <premis:rightsStatementIdentifierValue>rights-statement</premis:rightsStatementIdentifierValue>
                </premis:rightsStatementIdentifier>
                <premis:rightsBasis>other</premis:rightsBasis>
                <premis:otherRightsInformation>
                  <premis:otherRightsBasis>
                    <xsl:choose>
                      <xsl:when test="$h/c:rights">rights statement of the depositor</xsl:when>
                      <xsl:otherwise>unknown</xsl:otherwise>
                    </xsl:choose>
                  </premis:otherRightsBasis>
                  <premis:otherRightsNote>
                    <xsl:choose>
                      <xsl:when test="$h/c:rights"><xsl:value-of select="$h/c:rights"/></xsl:when>
                      <xsl:otherwise>no rights statement or licence was recorded with the capture (surrogate run, options rights and license); ask the depositor</xsl:otherwise>
                    </xsl:choose>
                  </premis:otherRightsNote>
                </premis:otherRightsInformation>
                <xsl:call-template name="rights-object-link"/>
              </premis:rightsStatement>
            </xsl:if>
          </premis:rights>
        </mets:xmlData>
      </mets:mdWrap>
    </mets:rightsMD>
  </xsl:template>

  <!-- The payload files as (path, size, sha256, sha512) nodes: the payload list when given,
       else the carrier's files (paths under data/). Each file's number is its position here. -->
  <xsl:variable name="use-payload" select="count($payload) &gt; 0"/>

  <!-- Whether a payload file belongs to a group: its element's name when the list names it;
       for a <file>, the role of its carrier file record (the first with the path "data/" +
       carrier path), "other" when the carrier does not list it. Looked up inline, in the
       carrier's document (key() looks in the context node's document): with the path and the
       number of the payload file taken before switching to it. -->

  <xsl:template name="file-group">
    <xsl:param name="use"/>
    <!-- the group's USE when it is not the role's name -->
    <xsl:param name="label" select="$use"/>
    <xsl:variable name="members">
      <xsl:choose>
        <xsl:when test="$use-payload">
          <xsl:if test="$payload[local-name() = $use]">x</xsl:if>
          <xsl:for-each select="$payload[self::file]">
            <xsl:variable name="path" select="@path"/>
            <xsl:for-each select="$carrier">
              <xsl:variable name="rec" select="key('file-by-bag-path', $path)"/>
              <xsl:if test="($rec and $rec[1][((@role = $use and not(@role = 'result' and starts-with(@path, 'finished-files/web/'))) or ($use = 'access' and @role = 'result' and starts-with(@path, 'finished-files/web/')))]) or (not($rec) and $use = 'other')">x</xsl:if>
            </xsl:for-each>
          </xsl:for-each>
        </xsl:when>
        <xsl:otherwise>
          <xsl:if test="$carrier/c:files/c:file[((@role = $use and not(@role = 'result' and starts-with(@path, 'finished-files/web/'))) or ($use = 'access' and @role = 'result' and starts-with(@path, 'finished-files/web/')))]">x</xsl:if>
        </xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:if test="string($members) != ''">
      <mets:fileGrp ID="fileGrp-{$label}" USE="{$label}">
        <xsl:choose>
          <xsl:when test="$use-payload">
            <xsl:for-each select="$payload">
              <xsl:variable name="n" select="position()"/>
              <xsl:variable name="path" select="@path"/>
              <xsl:variable name="size" select="@size"/>
              <xsl:variable name="sha256" select="@sha256"/>
              <xsl:variable name="named" select="local-name() = $use"/>
              <xsl:for-each select="$carrier[$named or current()/self::file]">
                <xsl:variable name="rec" select="key('file-by-bag-path', $path)"/>
                <xsl:if test="$named or ($rec and $rec[1][((@role = $use and not(@role = 'result' and starts-with(@path, 'finished-files/web/'))) or ($use = 'access' and @role = 'result' and starts-with(@path, 'finished-files/web/')))]) or (not($rec) and $use = 'other')">
                  <xsl:call-template name="mets-file">
                    <xsl:with-param name="n" select="$n"/>
                    <xsl:with-param name="path" select="$path"/>
                    <xsl:with-param name="size" select="$size"/>
                    <xsl:with-param name="sha256" select="$sha256"/>
                    <xsl:with-param name="rec" select="$rec"/>
                  </xsl:call-template>
                </xsl:if>
              </xsl:for-each>
            </xsl:for-each>
          </xsl:when>
          <xsl:otherwise>
            <xsl:for-each select="$carrier/c:files/c:file">
              <xsl:if test="((@role = $use and not(@role = 'result' and starts-with(@path, 'finished-files/web/'))) or ($use = 'access' and @role = 'result' and starts-with(@path, 'finished-files/web/')))">
                <xsl:call-template name="mets-file">
                  <xsl:with-param name="n" select="position()"/>
                  <xsl:with-param name="path" select="concat('data/', @path)"/>
                  <xsl:with-param name="size" select="@size"/>
                  <xsl:with-param name="sha256" select="@sha256"/>
                  <xsl:with-param name="rec" select="key('file-by-bag-path', concat('data/', @path))"/>
                </xsl:call-template>
              </xsl:if>
            </xsl:for-each>
          </xsl:otherwise>
        </xsl:choose>
      </mets:fileGrp>
    </xsl:if>
  </xsl:template>

  <!-- What names a payload file's METS file (file-T), amdSec (amd-T) and PREMIS object
       (object-T), T its token: its carrier file id (an NCName, never all digits), or, for a
       payload file the carrier does not list (the carrier itself, the report), its number n
       in the payload list. As one expression, computed for every file twice ($n is cut to
       nothing, from position 1 div 0, when there is a record):
         concat($rec[1]/@id, substring($n, 1 div not($rec))) -->

  <!-- GROUPID: "Group-" and the token of the file it is a version of (METS: a master and the
       derivatives made from it, in other file groups; Archivematica's readers take a file
       whose group is another file's as derived from that file). An export other software made
       from an original: the original's. A file a step made from exactly one file (the web copy
       of a model, the maps and previews DerivedMaps computes from one): that file's, except the
       web copy's index of every model (output kind web-index, written by the last WebCopy
       step), which is a version of none of them. Any other file is a group of its own. Call
       with the carrier as the context (keys). -->
  <xsl:template name="group-id">
    <xsl:param name="token"/>
    <xsl:param name="rec"/>
    <xsl:variable name="paired" select="key('file-by-id', $rec/@pairedWith)[@role = 'original'][$rec/@unrecordedProcessing = 'true' or $rec/@unrecordedProcessing = '1']"/>
    <xsl:variable name="step" select="key('step-by-id', $rec/@createdBy)"/>
    <xsl:variable name="inputs" select="key('result-by-step', $rec/@createdBy)/c:input/@file"/>
    <xsl:variable name="model" select="key('result-by-step', $step/preceding-sibling::c:step[@component = 'RtiFit'][c:param[@name = 'basis']/@value = $step/c:param[@name = 'model']/@value]/@id)/c:output/@file[$step/@component = 'DerivedMaps']"/>
    <xsl:choose>
      <xsl:when test="count($paired) = 1"><xsl:value-of select="concat('Group-', $paired/@id)"/></xsl:when>
      <xsl:when test="$step and count($inputs) = 1 and not(key('result-by-step', $rec/@createdBy)/c:output[@file = $rec/@id][@kind = 'web-index'])"><xsl:value-of select="concat('Group-', $inputs)"/></xsl:when>
      <xsl:when test="$step and not($inputs) and count($model) = 1"><xsl:value-of select="concat('Group-', $model)"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="concat('Group-', $token)"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template name="mets-file">
    <xsl:param name="n"/>
    <xsl:param name="path"/>
    <xsl:param name="size"/>
    <xsl:param name="sha256"/>
    <xsl:param name="rec"/>
    <xsl:variable name="token" select="concat($rec[1]/@id, substring($n, 1 div not($rec)))"/>
    <mets:file ID="file-{$token}" SIZE="{$size | $rec[1]/@size[not($size)]}"
               CHECKSUM="{$sha256 | $rec[1]/@sha256[not($sha256)]}" CHECKSUMTYPE="SHA-256"
               ADMID="amd-{$token}">
      <xsl:attribute name="GROUPID">
        <xsl:call-template name="group-id"><xsl:with-param name="token" select="$token"/><xsl:with-param name="rec" select="$rec[1]"/></xsl:call-template>
      </xsl:attribute>
      <xsl:attribute name="MIMETYPE">
        <xsl:choose>
          <xsl:when test="$rec/@mediaType != ''"><xsl:value-of select="$rec/@mediaType"/></xsl:when>
          <xsl:otherwise>
            <!-- files the carrier does not describe (itself, the report, ...): by name -->
            <xsl:variable name="key">
              <xsl:call-template name="format-key">
                <xsl:with-param name="rec" select="$rec"/>
                <xsl:with-param name="path" select="$path"/>
              </xsl:call-template>
            </xsl:variable>
            <xsl:choose>
              <xsl:when test="$key = 'XML'">application/xml</xsl:when>
              <xsl:when test="$key = 'HTML'">text/html</xsl:when>
              <xsl:when test="$key = 'PNG' or $key = 'PNG-written'">image/png</xsl:when>
              <xsl:when test="$key = 'JPEG'">image/jpeg</xsl:when>
              <xsl:when test="$key = 'DNG'">image/x-adobe-dng</xsl:when>
              <xsl:when test="$key = 'TIFF'">image/tiff</xsl:when>
              <xsl:when test="$key = 'PTM'">application/x-ptm</xsl:when>
              <xsl:when test="$key = 'RTI'">application/x-rti</xsl:when>
              <xsl:when test="$key = 'LP' or $key = 'TXT'">text/plain</xsl:when>
              <xsl:when test="$key = 'JSON'">application/json</xsl:when>
              <xsl:when test="$key = 'JavaScript'">text/javascript</xsl:when>
              <xsl:otherwise>application/octet-stream</xsl:otherwise>
            </xsl:choose>
          </xsl:otherwise>
        </xsl:choose>
      </xsl:attribute>
      <xsl:if test="$rec/@createdBy">
        <xsl:attribute name="CREATED"><xsl:value-of select="$carrier/c:data/c:result[@step = $rec/@createdBy]/@ended"/></xsl:attribute>
      </xsl:if>
      <mets:FLocat LOCTYPE="OTHER" OTHERLOCTYPE="BagIt payload path">
        <xsl:attribute name="xlink:href">
          <xsl:call-template name="href-of-path">
            <xsl:with-param name="path" select="$path"/>
          </xsl:call-template>
        </xsl:attribute>
      </mets:FLocat>
    </mets:file>
  </xsl:template>

  <!-- A payload path as a URI reference (xs:anyURI): '%', '#' and '?' written %25, %23 and %3F,
       which would otherwise start an escape, a fragment or a query ("100% of.txt" is no valid
       URI at all); XLink escapes the rest (spaces, letters beyond ASCII) itself. -->
  <xsl:template name="href-of-path">
    <xsl:param name="path"/>
    <xsl:variable name="percent">
      <xsl:call-template name="replace-all">
        <xsl:with-param name="text" select="$path"/>
        <xsl:with-param name="from" select="'%'"/>
        <xsl:with-param name="to" select="'%25'"/>
      </xsl:call-template>
    </xsl:variable>
    <xsl:variable name="hash">
      <xsl:call-template name="replace-all">
        <xsl:with-param name="text" select="$percent"/>
        <xsl:with-param name="from" select="'#'"/>
        <xsl:with-param name="to" select="'%23'"/>
      </xsl:call-template>
    </xsl:variable>
    <xsl:call-template name="replace-all">
      <xsl:with-param name="text" select="$hash"/>
      <xsl:with-param name="from" select="'?'"/>
      <xsl:with-param name="to" select="'%3F'"/>
    </xsl:call-template>
  </xsl:template>

  <xsl:template name="replace-all">
    <xsl:param name="text"/>
    <xsl:param name="from"/>
    <xsl:param name="to"/>
    <xsl:choose>
      <xsl:when test="contains($text, $from)">
        <xsl:value-of select="concat(substring-before($text, $from), $to)"/>
        <xsl:call-template name="replace-all">
          <xsl:with-param name="text" select="substring-after($text, $from)"/>
          <xsl:with-param name="from" select="$from"/>
          <xsl:with-param name="to" select="$to"/>
        </xsl:call-template>
      </xsl:when>
      <xsl:otherwise><xsl:value-of select="$text"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- The contents of one folder of the payload: `members` are the files under it at any depth
       (the in-folder key of `folder`; all files for data/ itself), in path order, each path
       with `skip` leading characters before the part relative to data/ ("data/" in the payload
       list, none in the carrier). A file directly in the folder is an Item; the first file of
       each sub-folder opens that folder's Directory div, which holds the rest of it. Each file
       is looked at once per folder above it. The payload list comes sorted by path, so each
       folder's files are together; should they not be, the sub-folder is still opened once
       (at the first of its files in document order) and holds all of them. -->
  <xsl:template name="folder">
    <xsl:param name="members"/>
    <xsl:param name="skip"/>
    <xsl:param name="folder" select="''"/>
    <xsl:param name="depth" select="0"/>
    <xsl:for-each select="$members">
      <xsl:variable name="rest" select="substring(@path, $skip + string-length($folder) + 1)"/>
      <xsl:choose>
        <xsl:when test="not(contains($rest, '/')) or $depth &gt;= $folder-depth">
          <mets:div TYPE="Item" LABEL="{$rest}">
            <xsl:variable name="here" select="."/>
            <xsl:variable name="path" select="concat(substring('data/', 1, 5 - $skip), @path)"/>
            <xsl:for-each select="$carrier">
              <xsl:variable name="rec" select="key('file-by-bag-path', $path)"/>
              <mets:fptr>
                <xsl:attribute name="FILEID">
                  <xsl:choose>
                    <!-- a payload file the carrier does not list: its number in the list -->
                    <xsl:when test="$rec"><xsl:value-of select="concat('file-', $rec[1]/@id)"/></xsl:when>
                    <xsl:otherwise><xsl:value-of select="concat('file-', count($here/preceding-sibling::*) + 1)"/></xsl:otherwise>
                  </xsl:choose>
                </xsl:attribute>
              </mets:fptr>
            </xsl:for-each>
          </mets:div>
        </xsl:when>
        <xsl:otherwise>
          <xsl:variable name="sub" select="concat($folder, substring-before($rest, '/'), '/')"/>
          <xsl:variable name="previous" select="preceding-sibling::*[1]/@path"/>
          <xsl:if test="not($previous and starts-with(substring($previous, $skip + 1), $sub)) and generate-id() = generate-id(key('in-folder', $sub)[1])">
            <mets:div TYPE="Directory" LABEL="{substring-before($rest, '/')}">
              <xsl:call-template name="folder">
                <xsl:with-param name="members" select="key('in-folder', $sub)"/>
                <xsl:with-param name="skip" select="$skip"/>
                <xsl:with-param name="folder" select="$sub"/>
                <xsl:with-param name="depth" select="$depth + 1"/>
              </xsl:call-template>
            </mets:div>
          </xsl:if>
        </xsl:otherwise>
      </xsl:choose>
    </xsl:for-each>
  </xsl:template>

  <!-- PREMIS objects ==================================================================== -->
  <xsl:template name="objects">
    <xsl:choose>
      <xsl:when test="$use-payload">
        <xsl:for-each select="$payload">
          <xsl:call-template name="premis-object">
            <xsl:with-param name="n" select="position()"/>
            <xsl:with-param name="path" select="@path"/>
            <xsl:with-param name="size" select="@size"/>
            <xsl:with-param name="sha256" select="@sha256"/>
            <xsl:with-param name="sha512" select="@sha512"/>
          </xsl:call-template>
        </xsl:for-each>
      </xsl:when>
      <xsl:otherwise>
        <xsl:for-each select="$carrier/c:files/c:file">
          <xsl:call-template name="premis-object">
            <xsl:with-param name="n" select="position()"/>
            <xsl:with-param name="path" select="concat('data/', @path)"/>
            <xsl:with-param name="size" select="@size"/>
            <xsl:with-param name="sha256" select="@sha256"/>
            <xsl:with-param name="sha512" select="''"/>
          </xsl:call-template>
        </xsl:for-each>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template name="premis-object">
    <xsl:param name="n"/>
    <xsl:param name="path"/>
    <xsl:param name="size"/>
    <xsl:param name="sha256"/>
    <xsl:param name="sha512"/>
    <xsl:for-each select="$carrier">
      <xsl:variable name="rec" select="key('file-by-bag-path', $path)"/>
      <xsl:variable name="token" select="concat($rec[1]/@id, substring($n, 1 div not($rec)))"/>
      <mets:amdSec ID="amd-{$token}">
      <mets:techMD ID="object-{$token}">
        <mets:mdWrap MDTYPE="PREMIS:OBJECT">
          <mets:xmlData>
            <premis:object xsi:type="premis:file" version="3.0">
              <premis:objectIdentifier>
                <premis:objectIdentifierType>BagIt payload path</premis:objectIdentifierType>
                <premis:objectIdentifierValue><xsl:value-of select="$path"/></premis:objectIdentifierValue>
              </premis:objectIdentifier>
              <xsl:if test="$rec">
                <premis:objectIdentifier>
                  <premis:objectIdentifierType>Surrogate carrier file id</premis:objectIdentifierType>
                  <premis:objectIdentifierValue><xsl:value-of select="$rec/@id"/></premis:objectIdentifierValue>
                </premis:objectIdentifier>
              </xsl:if>
              <xsl:if test="$rec/@unrecordedProcessing = 'true' or $rec/@unrecordedProcessing = '1'">
                <premis:significantProperties>
                  <premis:significantPropertiesType>provenance</premis:significantPropertiesType>
                  <premis:significantPropertiesValue>
                    <xsl:text>processed outside Surrogate: made by other software</xsl:text>
                    <xsl:for-each select="key('file-by-id', $rec/@pairedWith)"><xsl:value-of select="concat(' from data/', @path)"/></xsl:for-each>
                    <xsl:text>; what that software did is not recorded (carrier: unrecordedProcessing="true")</xsl:text>
                  </premis:significantPropertiesValue>
                </premis:significantProperties>
              </xsl:if>
              <!-- prior work: made outside Surrogate, by no event on record; what the file says
                   of its making is all that is known -->
              <xsl:if test="$rec/@role = 'prior'">
                <premis:significantProperties>
                  <premis:significantPropertiesType>provenance</premis:significantPropertiesType>
                  <premis:significantPropertiesValue>
                    <xsl:text>prior work: made outside Surrogate by another tool and found in the capture</xsl:text>
                    <xsl:choose>
                      <xsl:when test="$rec/@priorKind = 'lp'"><xsl:text> (a light file)</xsl:text></xsl:when>
                      <xsl:when test="$rec/@priorKind = 'rti'"><xsl:text> (an RTI result)</xsl:text></xsl:when>
                      <xsl:when test="$rec/@priorKind = 'log'"><xsl:text> (a processing log)</xsl:text></xsl:when>
                    </xsl:choose>
                    <xsl:text>; no Surrogate event made it, and how it was made is not recorded</xsl:text>
                  </premis:significantPropertiesValue>
                </premis:significantProperties>
                <premis:significantProperties>
                  <premis:significantPropertiesType>made by (as the file says)</premis:significantPropertiesType>
                  <premis:significantPropertiesValue>
                    <xsl:choose>
                      <xsl:when test="$rec/@madeBy != ''"><xsl:value-of select="$rec/@madeBy"/></xsl:when>
                      <xsl:otherwise>not known: the file does not say</xsl:otherwise>
                    </xsl:choose>
                  </premis:significantPropertiesValue>
                </premis:significantProperties>
              </xsl:if>
              <premis:objectCharacteristics>
                <premis:compositionLevel>0</premis:compositionLevel>
                <premis:fixity>
                  <premis:messageDigestAlgorithm>SHA-256</premis:messageDigestAlgorithm>
                  <premis:messageDigest><xsl:value-of select="$sha256 | $rec[1]/@sha256[not($sha256)]"/></premis:messageDigest>
                  <premis:messageDigestOriginator><xsl:value-of select="$software-agent"/></premis:messageDigestOriginator>
                </premis:fixity>
                <xsl:if test="$sha512 != ''">
                  <premis:fixity>
                    <premis:messageDigestAlgorithm>SHA-512</premis:messageDigestAlgorithm>
                    <premis:messageDigest><xsl:value-of select="$sha512"/></premis:messageDigest>
                    <premis:messageDigestOriginator><xsl:value-of select="$software-agent"/></premis:messageDigestOriginator>
                  </premis:fixity>
                </xsl:if>
                <premis:size><xsl:value-of select="$size | $rec[1]/@size[not($size)]"/></premis:size>
                <xsl:call-template name="premis-format">
                  <xsl:with-param name="rec" select="$rec"/>
                  <xsl:with-param name="path" select="$path"/>
                </xsl:call-template>
                <xsl:call-template name="creating-application">
                  <xsl:with-param name="rec" select="$rec"/>
                  <xsl:with-param name="path" select="$path"/>
                </xsl:call-template>
              </premis:objectCharacteristics>
              <!-- an audit's evidence: the name it had in the folder or package audited -->
              <xsl:variable name="evidence" select="key('evidence-by-path', $rec[1]/@path)"/>
              <premis:originalName>
                <xsl:choose>
                  <xsl:when test="$evidence"><xsl:value-of select="$evidence/@from"/></xsl:when>
                  <xsl:otherwise><xsl:value-of select="substring-after($path, 'data/')"/></xsl:otherwise>
                </xsl:choose>
              </premis:originalName>
              <!-- every file is part of the capture (the intellectual entity) -->
              <premis:relationship>
                <premis:relationshipType>structural</premis:relationshipType>
                <premis:relationshipSubType>is included in</premis:relationshipSubType>
                <premis:relatedObjectIdentifier>
                  <premis:relatedObjectIdentifierType>Surrogate package identifier</premis:relatedObjectIdentifierType>
                  <premis:relatedObjectIdentifierValue><xsl:value-of select="$objid"/></premis:relatedObjectIdentifierValue>
                </premis:relatedObjectIdentifier>
              </premis:relationship>
              <!-- a file a step made: derived from what the step used, by that step's event -->
              <xsl:for-each select="key('step-by-id', $rec/@createdBy)">
                <premis:relationship>
                  <premis:relationshipType>derivation</premis:relationshipType>
                  <premis:relationshipSubType>has source</premis:relationshipSubType>
                  <xsl:call-template name="step-sources">
                    <xsl:with-param name="step" select="."/>
                    <xsl:with-param name="as" select="'related'"/>
                  </xsl:call-template>
                  <premis:relatedEventIdentifier>
                    <premis:relatedEventIdentifierType>Surrogate event</premis:relatedEventIdentifierType>
                    <premis:relatedEventIdentifierValue><xsl:value-of select="concat('event-', @id)"/></premis:relatedEventIdentifierValue>
                  </premis:relatedEventIdentifier>
                </premis:relationship>
              </xsl:for-each>
              <xsl:for-each select="$rec/@pairedWith">
                <xsl:variable name="other" select="key('file-by-id', current())"/>
                <xsl:choose>
                  <!-- an export made by other software from the original of the same shot: a
                       derivation whose event is not on record -->
                  <xsl:when test="($rec/@unrecordedProcessing = 'true' or $rec/@unrecordedProcessing = '1') and $other/@role = 'original'">
                    <premis:relationship>
                      <premis:relationshipType>derivation</premis:relationshipType>
                      <premis:relationshipSubType>has source</premis:relationshipSubType>
                      <premis:relatedObjectIdentifier>
                        <premis:relatedObjectIdentifierType>BagIt payload path</premis:relatedObjectIdentifierType>
                        <premis:relatedObjectIdentifierValue><xsl:value-of select="concat('data/', $other/@path)"/></premis:relatedObjectIdentifierValue>
                      </premis:relatedObjectIdentifier>
                    </premis:relationship>
                  </xsl:when>
                  <xsl:otherwise>
                    <premis:relationship>
                      <premis:relationshipType>structural</premis:relationshipType>
                      <premis:relationshipSubType>is sibling of (same shot)</premis:relationshipSubType>
                      <premis:relatedObjectIdentifier>
                        <premis:relatedObjectIdentifierType>BagIt payload path</premis:relatedObjectIdentifierType>
                        <premis:relatedObjectIdentifierValue><xsl:value-of select="concat('data/', $other/@path)"/></premis:relatedObjectIdentifierValue>
                      </premis:relatedObjectIdentifier>
                    </premis:relationship>
                  </xsl:otherwise>
                </xsl:choose>
              </xsl:for-each>
              <xsl:if test="$rec/@role = 'original'">
                <premis:linkingEventIdentifier>
                  <premis:linkingEventIdentifierType>Surrogate event</premis:linkingEventIdentifierType>
                  <premis:linkingEventIdentifierValue>event-capture</premis:linkingEventIdentifierValue>
                </premis:linkingEventIdentifier>
              </xsl:if>
              <xsl:if test="key('evidence-by-path', $rec[1]/@path)">
                <premis:linkingEventIdentifier>
                  <premis:linkingEventIdentifierType>Surrogate event</premis:linkingEventIdentifierType>
                  <premis:linkingEventIdentifierValue>event-evidence-transfer</premis:linkingEventIdentifierValue>
                </premis:linkingEventIdentifier>
              </xsl:if>
              <!-- the step that made it (the events of the steps that used it list it as their
                   source; listing them here too would make the METS of a large capture
                   quadratic to derive) -->
              <xsl:for-each select="$rec/@createdBy">
                <premis:linkingEventIdentifier>
                  <premis:linkingEventIdentifierType>Surrogate event</premis:linkingEventIdentifierType>
                  <premis:linkingEventIdentifierValue><xsl:value-of select="concat('event-', .)"/></premis:linkingEventIdentifierValue>
                </premis:linkingEventIdentifier>
              </xsl:for-each>
              <xsl:if test="$path = $carrier-path">
                <xsl:for-each select="$carrier/c:header/c:run">
                  <premis:linkingEventIdentifier>
                    <premis:linkingEventIdentifierType>Surrogate event</premis:linkingEventIdentifierType>
                    <premis:linkingEventIdentifierValue><xsl:value-of select="concat('event-run-', @id)"/></premis:linkingEventIdentifierValue>
                  </premis:linkingEventIdentifier>
                </xsl:for-each>
              </xsl:if>
              <premis:linkingEventIdentifier>
                <premis:linkingEventIdentifierType>Surrogate event</premis:linkingEventIdentifierType>
                <premis:linkingEventIdentifierValue>event-message-digest</premis:linkingEventIdentifierValue>
              </premis:linkingEventIdentifier>
            </premis:object>
          </mets:xmlData>
        </mets:mdWrap>
      </mets:techMD>
      </mets:amdSec>
    </xsl:for-each>
  </xsl:template>

  <!-- The files a step used, as PREMIS identifiers (as = 'related': relatedObjectIdentifier,
       otherwise linkingObjectIdentifier with the role source).
       What the carrier records: the files the step lists as input and every image its results
       name (decoded, highlight, light, imageValue). What it does not list but the stage code
       reads (mappings/carrier-to-mets.md, "What each step used"): a step after decoding that
       names no file worked on the decoded images (the ImageDecode step's); RtiFit fitted to the
       light directions, which the lights step wrote to its .lp; DerivedMaps computed from the
       model of the RtiFit step whose basis it names, which that step wrote to its file; a
       ColourCorrection step that corrected measured the chart in the decoded images and changed
       the colours of all of them as the fit reads them, so it used them besides its chart image.
       Must stay the same expression as in carrier-to-crm.xsl (L10_had_input). -->
  <xsl:template name="step-sources">
    <xsl:param name="step"/>
    <xsl:param name="as"/>
    <xsl:for-each select="$carrier">
      <xsl:variable name="result" select="key('result-by-step', $step/@id)"/>
      <xsl:variable name="explicit" select="boolean($result/c:input/@file or $result/*/@image)"/>
      <xsl:variable name="decodeIds" select="$carrier/c:process/c:step[@component = 'ImageDecode']/@id"/>
      <xsl:variable name="useDecoded" select="(not($explicit) or ($step/@component = 'ColourCorrection' and $result/c:value[@name = 'outcome']/@value = 'corrected')) and $step/@component != 'CaptureIngest' and $step/@component != 'ImageDecode' and $step/@component != 'DerivedMaps'"/>
      <xsl:variable name="lights" select="key('result-by-step', $step/preceding-sibling::c:step[@component = 'LightDirections' or @component = 'LightsFromFile']/@id)/c:output[@kind = 'lp']/@file[$step/@component = 'RtiFit']"/>
      <xsl:variable name="model" select="key('result-by-step', $step/preceding-sibling::c:step[@component = 'RtiFit'][c:param[@name = 'basis']/@value = $step/c:param[@name = 'model']/@value]/@id)/c:output/@file[$step/@component = 'DerivedMaps']"/>
      <xsl:variable name="sources" select="$carrier/c:files/c:file[
          key('step-input', concat($step/@id, ' ', @id))
          or ($useDecoded and key('decoded-image', @id)[../../@step = $decodeIds])
          or @id = $lights or @id = $model]"/>
      <xsl:choose>
        <xsl:when test="$as = 'related'">
          <xsl:for-each select="$sources">
            <premis:relatedObjectIdentifier>
              <premis:relatedObjectIdentifierType>BagIt payload path</premis:relatedObjectIdentifierType>
              <premis:relatedObjectIdentifierValue><xsl:value-of select="concat('data/', @path)"/></premis:relatedObjectIdentifierValue>
            </premis:relatedObjectIdentifier>
          </xsl:for-each>
        </xsl:when>
        <xsl:otherwise>
          <xsl:for-each select="$sources">
            <xsl:call-template name="linking-object">
              <xsl:with-param name="file" select="."/>
              <xsl:with-param name="role" select="'source'"/>
            </xsl:call-template>
          </xsl:for-each>
        </xsl:otherwise>
      </xsl:choose>
    </xsl:for-each>
  </xsl:template>

  <!-- The format table (mappings/carrier-to-mets.md, "Formats"): the carrier's format name
       becomes the registry's name and version; the PRONOM identifier is the carrier's. -->
  <xsl:template name="format-key">
    <xsl:param name="rec"/>
    <xsl:param name="path"/>
    <xsl:variable name="lower" select="translate($path, 'ABCDEFGHIJKLMNOPQRSTUVWXYZ', 'abcdefghijklmnopqrstuvwxyz')"/>
    <xsl:choose>
      <xsl:when test="$rec and starts-with($rec/@format, 'PTM')">PTM</xsl:when>
      <xsl:when test="$rec and starts-with($rec/@format, 'RTI')">RTI</xsl:when>
      <xsl:when test="$rec and $rec/@format = 'PNG' and $rec/@createdBy">PNG-written</xsl:when>
      <xsl:when test="$rec"><xsl:value-of select="$rec/@format"/></xsl:when>
      <xsl:when test="substring($lower, string-length($lower) - 3) = '.xml'">XML</xsl:when>
      <xsl:when test="substring($lower, string-length($lower) - 4) = '.html'">HTML</xsl:when>
      <xsl:when test="substring($lower, string-length($lower) - 3) = '.png'">PNG</xsl:when>
      <xsl:when test="substring($lower, string-length($lower) - 3) = '.jpg' or substring($lower, string-length($lower) - 4) = '.jpeg'">JPEG</xsl:when>
      <xsl:when test="substring($lower, string-length($lower) - 3) = '.ptm'">PTM</xsl:when>
      <xsl:when test="substring($lower, string-length($lower) - 3) = '.rti'">RTI</xsl:when>
      <xsl:when test="substring($lower, string-length($lower) - 2) = '.lp'">LP</xsl:when>
      <xsl:when test="substring($lower, string-length($lower) - 3) = '.txt'">TXT</xsl:when>
      <xsl:when test="$mapping-edition &gt;= 2 and substring($lower, string-length($lower) - 4) = '.json'">JSON</xsl:when>
      <xsl:when test="$mapping-edition &gt;= 2 and substring($lower, string-length($lower) - 2) = '.js'">JavaScript</xsl:when>
      <xsl:otherwise>unknown</xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template name="premis-format">
    <xsl:param name="rec"/>
    <xsl:param name="path"/>
    <xsl:variable name="key">
      <xsl:call-template name="format-key">
        <xsl:with-param name="rec" select="$rec"/>
        <xsl:with-param name="path" select="$path"/>
      </xsl:call-template>
    </xsl:variable>
    <xsl:variable name="name">
      <xsl:choose>
        <xsl:when test="$key = 'DNG'">Digital Negative Format (DNG)</xsl:when>
        <xsl:when test="$key = 'JPEG'">JPEG</xsl:when>
        <xsl:when test="$key = 'TIFF'">Tagged Image File Format</xsl:when>
        <xsl:when test="$key = 'PNG' or $key = 'PNG-written'">Portable Network Graphics</xsl:when>
        <xsl:when test="$key = 'PTM'">Polynomial Texture Map (PTM)</xsl:when>
        <xsl:when test="$key = 'RTI'">Reflectance Transformation Imaging file (.rti)</xsl:when>
        <xsl:when test="$key = 'LP'">RTI light positions (.lp)</xsl:when>
        <xsl:when test="$key = 'XML'">Extensible Markup Language</xsl:when>
        <xsl:when test="$key = 'HTML'">Hypertext Markup Language</xsl:when>
        <xsl:when test="$key = 'TXT'">Plain Text File</xsl:when>
        <xsl:otherwise><xsl:value-of select="$key"/></xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:variable name="version">
      <xsl:choose>
        <xsl:when test="$key = 'PNG-written'">1.2</xsl:when>
        <xsl:when test="$key = 'PTM' and $rec">1.2</xsl:when>
        <xsl:when test="$key = 'RTI' and $rec/@format = 'RTI_HSH'">HSH 1.2</xsl:when>
        <xsl:when test="$key = 'XML'">1.0</xsl:when>
        <xsl:when test="$key = 'HTML'">5</xsl:when>
      </xsl:choose>
    </xsl:variable>
    <!-- The carrier's identifier, found from the file's bytes as DROID and Siegfried find it
         (src/formats/pronom.h, mappings/pronom.md); only the three files the carrier cannot
         record, itself, the report and the RO-Crate's metadata, take theirs from this table
         (tests/formats and tests/mapping check them). -->
    <xsl:variable name="puid">
      <xsl:choose>
        <xsl:when test="$rec"><xsl:value-of select="$rec/@puid"/></xsl:when>
        <xsl:when test="$key = 'XML' and $path = $carrier-path">fmt/101</xsl:when>
        <xsl:when test="$key = 'HTML'">fmt/471</xsl:when>
        <xsl:when test="$key = 'JSON' and $path = 'data/ro-crate-metadata.json'">fmt/817</xsl:when>
      </xsl:choose>
    </xsl:variable>
    <premis:format>
      <premis:formatDesignation>
        <premis:formatName><xsl:value-of select="$name"/></premis:formatName>
        <xsl:if test="$version != ''"><premis:formatVersion><xsl:value-of select="$version"/></premis:formatVersion></xsl:if>
      </premis:formatDesignation>
      <xsl:if test="$puid != ''">
        <premis:formatRegistry>
          <premis:formatRegistryName>PRONOM</premis:formatRegistryName>
          <premis:formatRegistryKey><xsl:value-of select="$puid"/></premis:formatRegistryKey>
          <premis:formatRegistryRole>specification</premis:formatRegistryRole>
        </premis:formatRegistry>
      </xsl:if>
      <xsl:if test="$rec/@mediaType != ''">
        <premis:formatNote><xsl:value-of select="concat('media type ', $rec/@mediaType)"/></premis:formatNote>
      </xsl:if>
      <xsl:if test="not($rec) and $key = 'JSON'">
        <premis:formatNote>media type application/json</premis:formatNote>
      </xsl:if>
      <xsl:if test="$mapping-edition &gt;= 2 and $puid = 'x-fmt/111' and $key = 'LP'">
        <premis:formatNote>PRONOM has no entry for .lp light-position files; PRONOM's tools (Siegfried, fido) identify them as Plain Text File (x-fmt/111)</premis:formatNote>
      </xsl:if>
      <xsl:if test="$rec and $rec/@format != $name">
        <premis:formatNote><xsl:value-of select="concat('carrier format name ', $rec/@format)"/></premis:formatNote>
      </xsl:if>
      <xsl:if test="$puid = ''">
        <premis:formatNote>
          <xsl:choose>
            <xsl:when test="$key = 'RTI'">PRONOM has no entry for the .rti format of Cultural Heritage Imaging's RTIBuilder and RTIViewer</xsl:when>
            <xsl:when test="$key = 'LP'">PRONOM has no entry for .lp light-position files (plain text: a count, then one line per image with its light direction)</xsl:when>
            <xsl:when test="$key = 'TXT'">PRONOM gives plain text (x-fmt/111) no signature: DROID and Siegfried name it from the file's extension only</xsl:when>
            <xsl:when test="$key = 'JSON'">PRONOM gives JSON (fmt/817) no signature: DROID and Siegfried name it from the file's extension only</xsl:when>
            <xsl:when test="$key = 'JavaScript'">PRONOM gives JavaScript (x-fmt/423) no signature: DROID and Siegfried name it from the file's extension only</xsl:when>
            <xsl:when test="$rec">no PRONOM identifier: no signature of the formats Surrogate identifies matches this file's bytes alone, or those of several formats do (mappings/pronom.md)</xsl:when>
            <xsl:otherwise>no PRONOM identifier known for this format</xsl:otherwise>
          </xsl:choose>
        </premis:formatNote>
      </xsl:if>
    </premis:format>
  </xsl:template>
  <xsl:template name="creating-application">
    <xsl:param name="rec"/>
    <xsl:param name="path"/>
    <xsl:choose>
      <xsl:when test="$rec/@createdBy">
        <xsl:variable name="step" select="$carrier/c:process/c:step[@id = $rec/@createdBy]"/>
        <premis:creatingApplication>
          <premis:creatingApplicationName><xsl:value-of select="concat('Surrogate ', $step/@component)"/></premis:creatingApplicationName>
          <premis:creatingApplicationVersion><xsl:value-of select="concat($step/@version, ' (Surrogate ', $surrogate/@version, ')')"/></premis:creatingApplicationVersion>
          <xsl:for-each select="$carrier/c:data/c:result[@step = $rec/@createdBy]/@ended">
            <premis:dateCreatedByApplication><xsl:value-of select="."/></premis:dateCreatedByApplication>
          </xsl:for-each>
        </premis:creatingApplication>
      </xsl:when>
      <xsl:when test="$rec/c:camera[@make or @model]">
        <premis:creatingApplication>
          <premis:creatingApplicationName><xsl:value-of select="normalize-space(concat($rec/c:camera/@make, ' ', $rec/c:camera/@model))"/></premis:creatingApplicationName>
          <xsl:if test="$rec/c:camera/@dateTimeOriginal != ''">
            <premis:dateCreatedByApplication><xsl:call-template name="exif-date"><xsl:with-param name="d" select="$rec/c:camera/@dateTimeOriginal"/></xsl:call-template></premis:dateCreatedByApplication>
          </xsl:if>
        </premis:creatingApplication>
      </xsl:when>
      <xsl:when test="$path = $carrier-path">
        <premis:creatingApplication>
          <premis:creatingApplicationName>Surrogate</premis:creatingApplicationName>
          <premis:creatingApplicationVersion><xsl:value-of select="$surrogate/@version"/></premis:creatingApplicationVersion>
          <premis:dateCreatedByApplication><xsl:value-of select="$carrier/c:header/c:modified"/></premis:dateCreatedByApplication>
        </premis:creatingApplication>
      </xsl:when>
    </xsl:choose>
  </xsl:template>

  <!-- EXIF "YYYY:MM:DD HH:MM:SS" -> "YYYY-MM-DDTHH:MM:SS"; other forms unchanged. -->
  <xsl:template name="exif-date">
    <xsl:param name="d"/>
    <xsl:choose>
      <xsl:when test="string-length($d) &gt;= 19 and substring($d, 5, 1) = ':' and substring($d, 8, 1) = ':'">
        <xsl:value-of select="concat(substring($d, 1, 4), '-', substring($d, 6, 2), '-', substring($d, 9, 2), 'T', substring($d, 12))"/>
      </xsl:when>
      <xsl:otherwise><xsl:value-of select="$d"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- PREMIS events ===================================================================== -->
  <!-- A run's command line: "surrogate COMMAND ARG ...", an argument with a space (or an empty
       one) in double quotes, as `surrogate info` prints it. -->
  <xsl:template name="command-line">
    <xsl:param name="run"/>
    <xsl:value-of select="concat('surrogate ', $run/@command)"/>
    <xsl:for-each select="$run/c:arg">
      <xsl:text> </xsl:text>
      <xsl:choose>
        <xsl:when test="contains(., ' ') or . = ''"><xsl:value-of select="concat('&quot;', ., '&quot;')"/></xsl:when>
        <xsl:otherwise><xsl:value-of select="."/></xsl:otherwise>
      </xsl:choose>
    </xsl:for-each>
  </xsl:template>

  <!-- An event type from the Library of Congress PREMIS eventType vocabulary
       (id.loc.gov/vocabulary/preservation/eventType), with its URI. -->
  <xsl:template name="event-type">
    <xsl:param name="label"/>
    <xsl:variable name="code">
      <xsl:choose>
        <xsl:when test="$label = 'capture'">cap</xsl:when>
        <xsl:when test="$label = 'creation'">cre</xsl:when>
        <xsl:when test="$label = 'interpreting'">int</xsl:when>
        <xsl:when test="$label = 'metadata extraction'">mee</xsl:when>
        <xsl:when test="$label = 'metadata modification'">mem</xsl:when>
        <xsl:when test="$label = 'modification'">mod</xsl:when>
        <xsl:when test="$label = 'message digest calculation'">mes</xsl:when>
        <xsl:when test="$label = 'information package creation'">ipc</xsl:when>
        <xsl:when test="$label = 'transfer'">tra</xsl:when>
      </xsl:choose>
    </xsl:variable>
    <premis:eventType authority="eventType" authorityURI="{$event-types}" valueURI="{concat($event-types, '/', $code)}"><xsl:value-of select="$label"/></premis:eventType>
  </xsl:template>

  <!-- Colour from a chart (the ColourCorrection step, docs/carrier.md; mappings/carrier-to-mets.md,
       "Colour correction"): what a reader of the event needs without the carrier. The figures
       are the carrier's strings, unrounded again. -->
  <xsl:template name="colour-figures">
    <xsl:param name="result"/>
    <xsl:param name="suffix"/>
    <xsl:value-of select="concat('mean ', $result/c:value[@name = concat('deltaE2000Mean', $suffix)]/@value,
                                 ', max ', $result/c:value[@name = concat('deltaE2000Max', $suffix)]/@value)"/>
  </xsl:template>
  <xsl:template name="colour-levels">
    <xsl:param name="result"/>
    <xsl:for-each select="$result/c:value[@name = 'qualityLevel']">
      <xsl:value-of select="concat('; ', @value)"/>
    </xsl:for-each>
  </xsl:template>
  <!-- The outcome in one line: "CIEDE2000 mean 1.2, max 3.1 after correction (mean 6.3, max 10.1
       before; mean 1.4, max 3.5 held out); FADGI 2023: 4 star; ...", or why the colours were
       kept ("colours not corrected: no ColorChecker found in ..."). -->
  <xsl:template name="colour-outcome">
    <xsl:param name="result"/>
    <xsl:choose>
      <xsl:when test="$result/c:value[@name = 'outcome']/@value = 'corrected'">
        <xsl:text>CIEDE2000 </xsl:text>
        <xsl:call-template name="colour-figures"><xsl:with-param name="result" select="$result"/><xsl:with-param name="suffix" select="''"/></xsl:call-template>
        <xsl:text> after correction (</xsl:text>
        <xsl:call-template name="colour-figures"><xsl:with-param name="result" select="$result"/><xsl:with-param name="suffix" select="'Before'"/></xsl:call-template>
        <xsl:text> before; </xsl:text>
        <xsl:call-template name="colour-figures"><xsl:with-param name="result" select="$result"/><xsl:with-param name="suffix" select="'HeldOut'"/></xsl:call-template>
        <xsl:text> held out)</xsl:text>
        <xsl:call-template name="colour-levels"><xsl:with-param name="result" select="$result"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise><xsl:value-of select="concat('colours not corrected: ', $result/c:value[@name = 'outcome']/@value)"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <!-- The correction in full: the chart's edition and where it was, the model and its
       coefficients, the figures and the quality levels. -->
  <xsl:template name="colour-detail">
    <xsl:param name="result"/>
    <xsl:variable name="chart" select="key('file-by-id', $result/c:input[@kind = 'chart']/@file)"/>
    <xsl:variable name="coefficients" select="$result/c:value[@name = 'coefficients']"/>
    <xsl:value-of select="concat('Colour corrected to a ', $result/c:value[@name = 'referenceTitle']/@value,
                                 ' (reference values ', $result/c:value[@name = 'reference']/@value)"/>
    <xsl:if test="$result/c:value[@name = 'referenceSource']/@value != ''"><xsl:value-of select="concat(': ', $result/c:value[@name = 'referenceSource']/@value)"/></xsl:if>
    <xsl:text>)</xsl:text>
    <xsl:if test="$chart"><xsl:value-of select="concat(', chart ', $result/c:value[@name = 'method']/@value, ' in data/', $chart/@path)"/></xsl:if>
    <xsl:value-of select="concat('; model ', $result/c:value[@name = 'model']/@value, ', coefficients ', $coefficients/@value)"/>
    <xsl:if test="$coefficients/@unit != ''"><xsl:value-of select="concat(' (', $coefficients/@unit, ')')"/></xsl:if>
    <xsl:value-of select="concat('; CIEDE2000 to the reference (', count($result/c:chartPatch[@deltaE2000 != '']), ' of ', count($result/c:chartPatch), ' patches measured): ')"/>
    <xsl:call-template name="colour-figures"><xsl:with-param name="result" select="$result"/><xsl:with-param name="suffix" select="'Before'"/></xsl:call-template>
    <xsl:text> before correction, </xsl:text>
    <xsl:call-template name="colour-figures"><xsl:with-param name="result" select="$result"/><xsl:with-param name="suffix" select="''"/></xsl:call-template>
    <xsl:text> after, </xsl:text>
    <xsl:call-template name="colour-figures"><xsl:with-param name="result" select="$result"/><xsl:with-param name="suffix" select="'HeldOut'"/></xsl:call-template>
    <xsl:text> held out (each patch corrected by a fit without it); quality levels</xsl:text>
    <xsl:for-each select="$result/c:value[@name = 'qualityLevel']">
      <xsl:choose>
        <xsl:when test="position() = 1"><xsl:value-of select="concat(': ', @value)"/></xsl:when>
        <xsl:otherwise><xsl:value-of select="concat('; ', @value)"/></xsl:otherwise>
      </xsl:choose>
    </xsl:for-each>
    <xsl:if test="not($result/c:value[@name = 'qualityLevel'])">: none recorded</xsl:if>
  </xsl:template>

  <!-- The libraries a step used, by the stage code (mappings/carrier-to-mets.md, "What each
       step used"): each header software entry named there, linked as a software agent. The
       decoder of each image is the one ImageDecode recorded. -->
  <xsl:template name="step-libraries">
    <xsl:param name="step"/>
    <xsl:variable name="result" select="$carrier/c:data/c:result[@step = $step/@id]"/>
    <xsl:variable name="names">
      <xsl:choose>
        <xsl:when test="$step/@component = 'CaptureIngest'">|LibRaw|Exiv2|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'ImageDecode' and $result/c:decoded/@decoder">|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'ImageDecode'">|LibRaw|OpenCV|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'SphereDetection'">|OpenCV|Eigen|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'HighlightDetection'">|OpenCV|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'LightDirections'">|Eigen|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'LightsFromFile'">|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'RtiFit'">|Eigen|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'DerivedMaps'">|OpenCV|Eigen|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'WebCopy'">|libjpeg-turbo|libjpeg|OpenCV|OpenSSL|</xsl:when>
        <xsl:when test="$step/@component = 'ColourCorrection'">|OpenCV|Eigen|</xsl:when>
      </xsl:choose>
    </xsl:variable>
    <xsl:for-each select="$carrier/c:header/c:software[@name != 'Surrogate']">
      <xsl:variable name="sw" select="."/>
      <xsl:if test="contains($names, concat('|', @name, '|')) or ($step/@component = 'ImageDecode' and $result/c:decoded[starts-with(@decoder, concat($sw/@name, ' '))])">
        <xsl:call-template name="linking-agent">
          <xsl:with-param name="type" select="'software'"/>
          <xsl:with-param name="value"><xsl:call-template name="software-id"/></xsl:with-param>
          <xsl:with-param name="role" select="'software library'"/>
        </xsl:call-template>
      </xsl:if>
    </xsl:for-each>
  </xsl:template>

  <!-- A header software entry's agent identifier: "name version", the version alone when it
       already begins with the name (OpenSSL reports "OpenSSL 3.0.13 30 Jan 2024"). -->
  <xsl:template name="software-id">
    <xsl:choose>
      <xsl:when test="starts-with(@version, concat(@name, ' '))"><xsl:value-of select="@version"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="concat(@name, ' ', @version)"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <!-- Surrogate itself, as the program that ran a step or command. -->
  <xsl:template name="surrogate-agent">
    <xsl:if test="$surrogate">
      <xsl:call-template name="linking-agent">
        <xsl:with-param name="type" select="'software'"/>
        <xsl:with-param name="value" select="concat($surrogate/@name, ' ', $surrogate/@version)"/>
        <xsl:with-param name="role" select="'executing program'"/>
      </xsl:call-template>
    </xsl:if>
  </xsl:template>

  <xsl:template name="linking-agent">
    <xsl:param name="type"/>
    <xsl:param name="value"/>
    <xsl:param name="role"/>
    <premis:linkingAgentIdentifier>
      <premis:linkingAgentIdentifierType><xsl:value-of select="$type"/></premis:linkingAgentIdentifierType>
      <premis:linkingAgentIdentifierValue><xsl:value-of select="$value"/></premis:linkingAgentIdentifierValue>
      <premis:linkingAgentRole><xsl:value-of select="$role"/></premis:linkingAgentRole>
    </premis:linkingAgentIdentifier>
  </xsl:template>

  <xsl:template name="linking-object">
    <xsl:param name="file"/>
    <xsl:param name="role"/>
    <premis:linkingObjectIdentifier>
      <premis:linkingObjectIdentifierType>BagIt payload path</premis:linkingObjectIdentifierType>
      <premis:linkingObjectIdentifierValue><xsl:value-of select="concat('data/', $file/@path)"/></premis:linkingObjectIdentifierValue>
      <premis:linkingObjectRole><xsl:value-of select="$role"/></premis:linkingObjectRole>
    </premis:linkingObjectIdentifier>
  </xsl:template>

  <xsl:template name="events">
    <xsl:variable name="originals" select="c:files/c:file[@role = 'original']"/>
    <!-- capture -->
    <mets:digiprovMD ID="event-capture">
      <mets:mdWrap MDTYPE="PREMIS:EVENT">
        <mets:xmlData>
          <premis:event version="3.0">
            <premis:eventIdentifier>
              <premis:eventIdentifierType>Surrogate event</premis:eventIdentifierType>
              <premis:eventIdentifierValue>event-capture</premis:eventIdentifierValue>
            </premis:eventIdentifier>
            <xsl:call-template name="event-type"><xsl:with-param name="label" select="'capture'"/></xsl:call-template>
            <xsl:variable name="shot">
              <xsl:for-each select="$originals/c:camera/@dateTimeOriginal">
                <xsl:sort select="."/>
                <xsl:if test="position() = 1"><xsl:call-template name="exif-date"><xsl:with-param name="d" select="."/></xsl:call-template></xsl:if>
              </xsl:for-each>
            </xsl:variable>
            <xsl:variable name="zone" select="substring($shot, 20)"/>
            <premis:eventDateTime>
              <xsl:choose>
                <xsl:when test="$shot != ''"><xsl:value-of select="$shot"/></xsl:when>
                <xsl:otherwise><xsl:value-of select="c:header/c:created"/></xsl:otherwise>
              </xsl:choose>
            </premis:eventDateTime>
            <premis:eventDetailInformation>
              <premis:eventDetail><xsl:value-of select="concat('Highlight-RTI capture of ', count($originals), ' images: ', c:header/c:title)"/></premis:eventDetail>
            </premis:eventDetailInformation>
            <premis:eventDetailInformation>
              <premis:eventDetail>
                <xsl:choose>
                  <xsl:when test="$shot = ''">date: the camera recorded no shooting time (EXIF DateTimeOriginal); the date given is when the record was made (UTC)</xsl:when>
                  <xsl:when test="contains($zone, 'Z') or contains($zone, '+') or contains($zone, '-')">date: the first shot, from the camera clock (EXIF DateTimeOriginal with its time zone)</xsl:when>
                  <xsl:otherwise>date: the first shot, from the camera clock (EXIF DateTimeOriginal); local time of the camera, time zone not recorded</xsl:otherwise>
                </xsl:choose>
              </premis:eventDetail>
            </premis:eventDetailInformation>
            <premis:eventOutcomeInformation>
              <premis:eventOutcome>success</premis:eventOutcome>
            </premis:eventOutcomeInformation>
            <xsl:for-each select="c:header/c:creator">
              <xsl:call-template name="linking-agent">
                <xsl:with-param name="type" select="'person'"/>
                <xsl:with-param name="value" select="normalize-space(.)"/>
                <xsl:with-param name="role" select="@role"/>
              </xsl:call-template>
            </xsl:for-each>
            <xsl:for-each select="$originals/c:camera[count(. | key('camera', concat(@make, '|', @model, '|', @serial))[1]) = 1]">
              <xsl:call-template name="linking-agent">
                <xsl:with-param name="type" select="'camera'"/>
                <xsl:with-param name="value" select="normalize-space(concat(@make, ' ', @model, ' ', @serial))"/>
                <xsl:with-param name="role" select="'capture device'"/>
              </xsl:call-template>
            </xsl:for-each>
            <xsl:for-each select="$originals">
              <xsl:call-template name="linking-object">
                <xsl:with-param name="file" select="."/>
                <xsl:with-param name="role" select="'outcome'"/>
              </xsl:call-template>
            </xsl:for-each>
          </premis:event>
        </mets:xmlData>
      </mets:mdWrap>
    </mets:digiprovMD>

    <!-- an audit: the evidence copied byte for byte from the folder or package audited -->
    <xsl:for-each select="c:header/c:audited">
      <mets:digiprovMD ID="event-evidence-transfer">
        <mets:mdWrap MDTYPE="PREMIS:EVENT">
          <mets:xmlData>
            <premis:event version="3.0">
              <premis:eventIdentifier>
                <premis:eventIdentifierType>Surrogate event</premis:eventIdentifierType>
                <premis:eventIdentifierValue>event-evidence-transfer</premis:eventIdentifierValue>
              </premis:eventIdentifier>
              <xsl:call-template name="event-type"><xsl:with-param name="label" select="'transfer'"/></xsl:call-template>
              <premis:eventDateTime><xsl:value-of select="@copied"/></premis:eventDateTime>
              <premis:eventDetailInformation>
                <premis:eventDetail>
                  <xsl:value-of select="concat('Evidence for the audit (surrogate audit) copied byte for byte from the ', @kind, ' ', @source)"/>
                  <xsl:if test="@packageSha256">
                    <xsl:value-of select="concat(' (', @packageSize, ' bytes, SHA-256 ', @packageSha256, ')')"/>
                  </xsl:if>
                  <xsl:value-of select="concat(': ', count(c:evidence), ' files')"/>
                </premis:eventDetail>
              </premis:eventDetailInformation>
              <xsl:for-each select="c:evidence">
                <premis:eventDetailInformation>
                  <premis:eventDetail><xsl:value-of select="concat(@from, ' -> data/', @path, ': ', @size, ' bytes, SHA-256 ', @sha256, ' as read at the source')"/></premis:eventDetail>
                </premis:eventDetailInformation>
              </xsl:for-each>
              <premis:eventOutcomeInformation>
                <premis:eventOutcome>success</premis:eventOutcome>
                <premis:eventOutcomeDetail>
                  <premis:eventOutcomeDetailNote>each copy has the size and SHA-256 read from its source; surrogate verify checks them against the copies again (carrier.evidence)</premis:eventOutcomeDetailNote>
                </premis:eventOutcomeDetail>
              </premis:eventOutcomeInformation>
              <xsl:call-template name="surrogate-agent"/>
              <xsl:for-each select="c:evidence">
                <xsl:call-template name="linking-object">
                  <xsl:with-param name="file" select="."/>
                  <xsl:with-param name="role" select="'outcome'"/>
                </xsl:call-template>
              </xsl:for-each>
            </premis:event>
          </mets:xmlData>
        </mets:mdWrap>
      </mets:digiprovMD>
    </xsl:for-each>

    <!-- each recorded command run (the history of the record), oldest first -->
    <xsl:for-each select="c:header/c:run">
      <mets:digiprovMD ID="event-run-{@id}">
        <mets:mdWrap MDTYPE="PREMIS:EVENT">
          <mets:xmlData>
            <premis:event version="3.0">
              <premis:eventIdentifier>
                <premis:eventIdentifierType>Surrogate event</premis:eventIdentifierType>
                <premis:eventIdentifierValue><xsl:value-of select="concat('event-run-', @id)"/></premis:eventIdentifierValue>
              </premis:eventIdentifier>
              <xsl:call-template name="event-type"><xsl:with-param name="label" select="'metadata modification'"/></xsl:call-template>
              <premis:eventDateTime><xsl:value-of select="@started"/></premis:eventDateTime>
              <premis:eventDetailInformation>
                <premis:eventDetail><xsl:call-template name="command-line"><xsl:with-param name="run" select="."/></xsl:call-template></premis:eventDetail>
              </premis:eventDetailInformation>
              <premis:eventDetailInformation>
                <premis:eventDetail>
                  <xsl:value-of select="concat('Surrogate command run ', @id, ' by ', normalize-space(@who), ', started ', @started, ', ended ', @ended, ', ', @outcome)"/>
                  <xsl:if test="@id = $state-run and $carrier/c:data/c:result">
                    <xsl:text>; made the record's current state, pipeline steps:</xsl:text>
                    <xsl:for-each select="$carrier/c:process/c:step[@id = $carrier/c:data/c:result/@step]"><xsl:value-of select="concat(' event-', @id)"/></xsl:for-each>
                  </xsl:if>
                </premis:eventDetail>
              </premis:eventDetailInformation>
              <premis:eventOutcomeInformation>
                <premis:eventOutcome>
                  <xsl:choose>
                    <xsl:when test="@outcome = 'completed'">success</xsl:when>
                    <xsl:otherwise>failure</xsl:otherwise>
                  </xsl:choose>
                </premis:eventOutcome>
                <xsl:for-each select="c:note">
                  <premis:eventOutcomeDetail>
                    <premis:eventOutcomeDetailNote><xsl:value-of select="."/></premis:eventOutcomeDetailNote>
                  </premis:eventOutcomeDetail>
                </xsl:for-each>
              </premis:eventOutcomeInformation>
              <xsl:call-template name="linking-agent">
                <xsl:with-param name="type" select="'person'"/>
                <xsl:with-param name="value" select="normalize-space(@who)"/>
                <xsl:with-param name="role" select="'implementer'"/>
              </xsl:call-template>
              <xsl:call-template name="surrogate-agent"/>
              <!-- the record is written and checked against its schema with libxml2 -->
              <xsl:for-each select="$carrier/c:header/c:software[@name = 'libxml2']">
                <xsl:call-template name="linking-agent">
                  <xsl:with-param name="type" select="'software'"/>
                  <xsl:with-param name="value"><xsl:call-template name="software-id"/></xsl:with-param>
                  <xsl:with-param name="role" select="'software library'"/>
                </xsl:call-template>
              </xsl:for-each>
              <premis:linkingObjectIdentifier>
                <premis:linkingObjectIdentifierType>BagIt payload path</premis:linkingObjectIdentifierType>
                <premis:linkingObjectIdentifierValue><xsl:value-of select="$carrier-path"/></premis:linkingObjectIdentifierValue>
                <premis:linkingObjectRole>outcome</premis:linkingObjectRole>
              </premis:linkingObjectIdentifier>
            </premis:event>
          </mets:xmlData>
        </mets:mdWrap>
      </mets:digiprovMD>
    </xsl:for-each>

    <!-- each pipeline step -->
    <xsl:for-each select="c:process/c:step">
      <xsl:variable name="step" select="."/>
      <xsl:variable name="result" select="$carrier/c:data/c:result[@step = $step/@id]"/>
      <mets:digiprovMD ID="event-{@id}">
        <mets:mdWrap MDTYPE="PREMIS:EVENT">
          <mets:xmlData>
            <premis:event version="3.0">
              <premis:eventIdentifier>
                <premis:eventIdentifierType>Surrogate event</premis:eventIdentifierType>
                <premis:eventIdentifierValue><xsl:value-of select="concat('event-', @id)"/></premis:eventIdentifierValue>
              </premis:eventIdentifier>
              <xsl:call-template name="event-type">
                <xsl:with-param name="label">
                  <xsl:choose>
                    <xsl:when test="@component = 'ColourCorrection' and $result/c:value[@name = 'outcome']/@value = 'corrected'">modification</xsl:when>
                    <xsl:when test="$result/c:output">creation</xsl:when>
                    <xsl:when test="@component = 'ImageDecode'">interpreting</xsl:when>
                    <xsl:otherwise>metadata extraction</xsl:otherwise>
                  </xsl:choose>
                </xsl:with-param>
              </xsl:call-template>
              <premis:eventDateTime>
                <xsl:choose>
                  <xsl:when test="$result"><xsl:value-of select="$result/@started"/></xsl:when>
                  <xsl:otherwise><xsl:value-of select="$carrier/c:header/c:modified"/></xsl:otherwise>
                </xsl:choose>
              </premis:eventDateTime>
              <premis:eventDetailInformation>
                <premis:eventDetail>
                  <xsl:value-of select="concat('Pipeline step ', @id, ': ', @component, ' ', @version)"/>
                  <xsl:if test="@algorithm != ''"><xsl:value-of select="concat(' (', @algorithm, ')')"/></xsl:if>
                  <xsl:if test="c:description != ''"><xsl:value-of select="concat(': ', normalize-space(c:description))"/></xsl:if>
                  <xsl:if test="$result/@ended"><xsl:value-of select="concat('; ended ', $result/@ended)"/></xsl:if>
                  <xsl:if test="c:param">
                    <xsl:text>; parameters:</xsl:text>
                    <xsl:for-each select="c:param"><xsl:value-of select="concat(' ', @name, '=', @value)"/></xsl:for-each>
                  </xsl:if>
                </premis:eventDetail>
              </premis:eventDetailInformation>
              <xsl:if test="@component = 'ColourCorrection' and $result/c:value[@name = 'outcome']/@value = 'corrected'">
                <premis:eventDetailInformation>
                  <premis:eventDetail><xsl:call-template name="colour-detail"><xsl:with-param name="result" select="$result"/></xsl:call-template></premis:eventDetail>
                </premis:eventDetailInformation>
              </xsl:if>
              <premis:eventOutcomeInformation>
                <premis:eventOutcome>
                  <xsl:choose>
                    <xsl:when test="$result/@status = 'completed'">success</xsl:when>
                    <xsl:when test="$result/@status = 'failed'">failure</xsl:when>
                    <xsl:otherwise>not run</xsl:otherwise>
                  </xsl:choose>
                </premis:eventOutcome>
                <xsl:if test="@component = 'ColourCorrection' and $result/c:value[@name = 'outcome']">
                  <premis:eventOutcomeDetail>
                    <premis:eventOutcomeDetailNote><xsl:call-template name="colour-outcome"><xsl:with-param name="result" select="$result"/></xsl:call-template></premis:eventOutcomeDetailNote>
                  </premis:eventOutcomeDetail>
                </xsl:if>
                <xsl:for-each select="$result/c:value">
                  <premis:eventOutcomeDetail>
                    <premis:eventOutcomeDetailNote><xsl:value-of select="normalize-space(concat(@name, ' = ', @value, ' ', @unit))"/></premis:eventOutcomeDetailNote>
                  </premis:eventOutcomeDetail>
                </xsl:for-each>
                <xsl:for-each select="$carrier/c:log/c:entry[@step = $step/@id][@level = 'warning' or @level = 'error']">
                  <premis:eventOutcomeDetail>
                    <premis:eventOutcomeDetailNote><xsl:value-of select="concat(@level, ': ', normalize-space(.))"/></premis:eventOutcomeDetailNote>
                  </premis:eventOutcomeDetail>
                </xsl:for-each>
                <xsl:for-each select="c:intervention">
                  <premis:eventOutcomeDetail>
                    <premis:eventOutcomeDetailNote>
                      <xsl:value-of select="concat('intervention ', @kind, ' on ', @target)"/>
                      <xsl:if test="@value != ''"><xsl:value-of select="concat(' = ', @value)"/></xsl:if>
                      <xsl:value-of select="concat(' by ', @who, ' at ', @time, ': ', normalize-space(.))"/>
                    </premis:eventOutcomeDetailNote>
                  </premis:eventOutcomeDetail>
                </xsl:for-each>
              </premis:eventOutcomeInformation>
              <xsl:if test="$operator != '' and $result">
                <xsl:call-template name="linking-agent">
                  <xsl:with-param name="type" select="'person'"/>
                  <xsl:with-param name="value" select="$operator"/>
                  <xsl:with-param name="role" select="'implementer'"/>
                </xsl:call-template>
              </xsl:if>
              <xsl:call-template name="linking-agent">
                <xsl:with-param name="type" select="'software'"/>
                <xsl:with-param name="value" select="concat('Surrogate ', @component, ' ', @version)"/>
                <xsl:with-param name="role" select="'executing program'"/>
              </xsl:call-template>
              <xsl:call-template name="surrogate-agent"/>
              <xsl:call-template name="step-libraries"><xsl:with-param name="step" select="."/></xsl:call-template>
              <xsl:for-each select="c:intervention">
                <xsl:if test="not(preceding-sibling::c:intervention[normalize-space(@who) = normalize-space(current()/@who)])">
                  <xsl:call-template name="linking-agent">
                    <xsl:with-param name="type" select="'person'"/>
                    <xsl:with-param name="value" select="normalize-space(@who)"/>
                    <xsl:with-param name="role" select="'intervened'"/>
                  </xsl:call-template>
                </xsl:if>
              </xsl:for-each>
              <xsl:call-template name="step-sources">
                <xsl:with-param name="step" select="."/>
                <xsl:with-param name="as" select="'linking'"/>
              </xsl:call-template>
              <!-- what it wrote: its outputs, and any file that names it as its maker -->
              <xsl:for-each select="key('file-by-id', $result/c:output/@file) | key('file-by-creator', @id)">
                <xsl:call-template name="linking-object">
                  <xsl:with-param name="file" select="."/>
                  <xsl:with-param name="role" select="'outcome'"/>
                </xsl:call-template>
              </xsl:for-each>
            </premis:event>
          </mets:xmlData>
        </mets:mdWrap>
      </mets:digiprovMD>
    </xsl:for-each>

    <!-- message digest calculation and packaging -->
    <xsl:call-template name="package-event">
      <xsl:with-param name="id" select="'event-message-digest'"/>
      <xsl:with-param name="type" select="'message digest calculation'"/>
      <xsl:with-param name="detail" select="'SHA-256 and SHA-512 of every payload and tag file, computed in one read while packing (BagIt manifests)'"/>
    </xsl:call-template>
    <xsl:call-template name="package-event">
      <xsl:with-param name="id" select="'event-packaging'"/>
      <xsl:with-param name="type" select="'information package creation'"/>
      <xsl:with-param name="detail" select="concat('BagIt 1.0 package ', $objid, ' written; metadata derived from the carrier by carrier-to-mets.xsl and carrier-to-crm.xsl')"/>
    </xsl:call-template>
  </xsl:template>

  <xsl:template name="package-event">
    <xsl:param name="id"/>
    <xsl:param name="type"/>
    <xsl:param name="detail"/>
    <mets:digiprovMD ID="{$id}">
      <mets:mdWrap MDTYPE="PREMIS:EVENT">
        <mets:xmlData>
          <premis:event version="3.0">
            <premis:eventIdentifier>
              <premis:eventIdentifierType>Surrogate event</premis:eventIdentifierType>
              <premis:eventIdentifierValue><xsl:value-of select="$id"/></premis:eventIdentifierValue>
            </premis:eventIdentifier>
            <xsl:call-template name="event-type"><xsl:with-param name="label" select="$type"/></xsl:call-template>
            <premis:eventDateTime><xsl:value-of select="$pack-time"/></premis:eventDateTime>
            <premis:eventDetailInformation>
              <premis:eventDetail><xsl:value-of select="$detail"/></premis:eventDetail>
            </premis:eventDetailInformation>
            <premis:eventOutcomeInformation>
              <premis:eventOutcome>success</premis:eventOutcome>
            </premis:eventOutcomeInformation>
            <xsl:call-template name="linking-agent">
              <xsl:with-param name="type" select="'software'"/>
              <xsl:with-param name="value" select="$software-agent"/>
              <xsl:with-param name="role" select="'executing program'"/>
            </xsl:call-template>
            <xsl:if test="$id = 'event-packaging'">
              <premis:linkingObjectIdentifier>
                <premis:linkingObjectIdentifierType>Surrogate package identifier</premis:linkingObjectIdentifierType>
                <premis:linkingObjectIdentifierValue><xsl:value-of select="$objid"/></premis:linkingObjectIdentifierValue>
                <premis:linkingObjectRole>outcome</premis:linkingObjectRole>
              </premis:linkingObjectIdentifier>
            </xsl:if>
          </premis:event>
        </mets:xmlData>
      </mets:mdWrap>
    </mets:digiprovMD>
  </xsl:template>

  <!-- PREMIS agents ===================================================================== -->
  <xsl:template name="agent">
    <xsl:param name="id"/>
    <xsl:param name="type"/>
    <xsl:param name="value"/>
    <xsl:param name="name"/>
    <xsl:param name="agent-type"/>
    <xsl:param name="version" select="''"/>
    <xsl:param name="note" select="''"/>
    <mets:digiprovMD ID="{$id}">
      <mets:mdWrap MDTYPE="PREMIS:AGENT">
        <mets:xmlData>
          <premis:agent version="3.0">
            <premis:agentIdentifier>
              <premis:agentIdentifierType><xsl:value-of select="$type"/></premis:agentIdentifierType>
              <premis:agentIdentifierValue><xsl:value-of select="$value"/></premis:agentIdentifierValue>
            </premis:agentIdentifier>
            <premis:agentName><xsl:value-of select="$name"/></premis:agentName>
            <premis:agentType><xsl:value-of select="$agent-type"/></premis:agentType>
            <xsl:if test="$version != ''"><premis:agentVersion><xsl:value-of select="$version"/></premis:agentVersion></xsl:if>
            <xsl:if test="$note != ''"><premis:agentNote><xsl:value-of select="$note"/></premis:agentNote></xsl:if>
          </premis:agent>
        </mets:xmlData>
      </mets:mdWrap>
    </mets:digiprovMD>
  </xsl:template>

  <!-- Each agent once: events link to them by (type, value). -->
  <xsl:template name="agents">
    <xsl:if test="not($packer-is-surrogate)">
      <xsl:call-template name="agent">
        <xsl:with-param name="id" select="'agent-packer'"/>
        <xsl:with-param name="type" select="'software'"/>
        <xsl:with-param name="value" select="$software-agent"/>
        <xsl:with-param name="name" select="$software-agent"/>
        <xsl:with-param name="agent-type" select="'software'"/>
        <xsl:with-param name="note" select="'wrote the BagIt package and its manifests'"/>
      </xsl:call-template>
    </xsl:if>
    <xsl:for-each select="c:header/c:software">
      <xsl:call-template name="agent">
        <xsl:with-param name="id" select="concat('agent-software-', position())"/>
        <xsl:with-param name="type" select="'software'"/>
        <xsl:with-param name="value"><xsl:call-template name="software-id"/></xsl:with-param>
        <xsl:with-param name="name" select="@name"/>
        <xsl:with-param name="agent-type" select="'software'"/>
        <xsl:with-param name="version" select="@version"/>
        <xsl:with-param name="note">
          <xsl:value-of select="@role"/>
          <xsl:if test="@name = 'Surrogate' and $packer-is-surrogate">; also wrote the BagIt package and its manifests</xsl:if>
        </xsl:with-param>
      </xsl:call-template>
    </xsl:for-each>
    <xsl:for-each select="c:process/c:step[count(. | key('stage', concat(@component, ' ', @version))[1]) = 1]">
      <xsl:call-template name="agent">
        <xsl:with-param name="id" select="concat('agent-stage-', position())"/>
        <xsl:with-param name="type" select="'software'"/>
        <xsl:with-param name="value" select="concat('Surrogate ', @component, ' ', @version)"/>
        <xsl:with-param name="name" select="concat('Surrogate ', @component)"/>
        <xsl:with-param name="agent-type" select="'software'"/>
        <xsl:with-param name="version" select="@version"/>
        <xsl:with-param name="note" select="concat('pipeline stage of Surrogate ', $surrogate/@version, ' run on ', $carrier/c:header/c:machine/@hostname, ' (', $carrier/c:header/c:machine/@os, ', ', $carrier/c:header/c:machine/@architecture, ')')"/>
      </xsl:call-template>
    </xsl:for-each>
    <xsl:for-each select="(c:header/c:creator | c:header/c:run/@who | c:process/c:step/c:intervention/@who | c:log/c:entry/@who)[count(. | key('person', normalize-space(.))[1]) = 1][normalize-space(.) != '']">
      <xsl:call-template name="agent">
        <xsl:with-param name="id" select="concat('agent-person-', position())"/>
        <xsl:with-param name="type" select="'person'"/>
        <xsl:with-param name="value" select="normalize-space(.)"/>
        <xsl:with-param name="name" select="normalize-space(.)"/>
        <xsl:with-param name="agent-type" select="'person'"/>
        <xsl:with-param name="note" select="self::c:creator/@role"/>
      </xsl:call-template>
    </xsl:for-each>
    <xsl:for-each select="c:files/c:file[@role = 'original']/c:camera[count(. | key('camera', concat(@make, '|', @model, '|', @serial))[1]) = 1]">
      <xsl:call-template name="agent">
        <xsl:with-param name="id" select="concat('agent-camera-', position())"/>
        <xsl:with-param name="type" select="'camera'"/>
        <xsl:with-param name="value" select="normalize-space(concat(@make, ' ', @model, ' ', @serial))"/>
        <xsl:with-param name="name" select="normalize-space(concat(@make, ' ', @model))"/>
        <xsl:with-param name="agent-type" select="'hardware'"/>
        <xsl:with-param name="note" select="normalize-space(concat('serial ', @serial, '; lens ', @lens))"/>
      </xsl:call-template>
    </xsl:for-each>
  </xsl:template>

</xsl:stylesheet>
