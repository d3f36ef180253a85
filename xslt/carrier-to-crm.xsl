<?xml version="1.0" encoding="UTF-8"?>
<!--
  Surrogate carrier -> CIDOC-CRM 7.1.3 + CRMdig 5.0, as RDF/XML (metadata/crm.rdf).

  Input: a carrier (namespace urn:surrogate:carrier:1, schema xsd/carrier.xsd).
  What it says:
    the digitization (crmdig:D2) of the object (E22, the carrier's title) on the camera(s)
      (crmdig:D8: make, model, serial, lens), carried out by the creators (E21), created the
      original images (crmdig:D9); the processing (E7) continued it (P134) and consists of (P9)
      the steps that ran, the command runs and the interventions, all within its time-span;
    each pipeline step is a software execution (crmdig:D10) that used software (crmdig:L23,
      crmdig:D14 with name and version), read inputs (crmdig:L10), wrote outputs (crmdig:L11),
      used parameters (crmdig:L13), ran on the workstation (crmdig:L12, a D8) within a time-span
      (P4, E52), continued the step before it (P134), and was motivated by (P17) human
      interventions (E7 carried out by an E21, with the reason as a note);
    each recorded command run (header/run: surrogate run, lights, pack; completed or failed) is an
      activity (E7) of the session, carried out by a person (E21), with its command line, its
      notes and outcome, continuing the run before it (P134); the run that made the record's
      current state consists of (P9) the steps that ran;
    each file is a data object (crmdig:D9) identified by its path and its SHA-256 (E42), with its
      size (E54, bytes) and format (E55); results are also visual items (E36) representing
      (P138) the object; an export made by other software is the output of a machine event
      (crmdig:D7) that read its original; every file is subject to (P104) the rights (E30)
      when the carrier records any;
    the document states the CRM and CRMdig versions it uses (rdfs:comment, dcterms:conformsTo).
  Every class and property used, with its domain and range, is in
  tests/mapping/data/crm-terms.tsv (checked by the tests).
  Parameters:
    crmdig-ns  the CRMdig namespace (default the current one, of versions 4 and 5; older data
               uses http://www.ics.forth.gr/isl/CRMdig/)
    base-uri   prefix of the URIs minted for this capture (default the capture identifier,
               urn:surrogate:capture: followed by the SHA-256 of the carrier's first file, and
               "/"; pack -\-base-uri, recorded in bag-info Surrogate-Base-URI)
    package-id the package identifier (bag-info Surrogate-Package-Identifier); when given, the
               package is a digital object named by it, identified by it, made of the files
               and about the digitization
    previous-package-id  the package an earlier pack of this capture made (bag-info
               Surrogate-Previous-Package-Identifier): this package shows features of it (P130)
  The mapping is explained, element by element, in mappings/carrier-to-crm.md.
  Re-derive by hand: xsltproc carrier-to-crm.xsl data/assembly-files/carrier.xml
  Output is deterministic: the same carrier gives the same bytes.
-->
<xsl:stylesheet version="1.0"
    xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:c="urn:surrogate:carrier:1"
    xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#"
    xmlns:rdfs="http://www.w3.org/2000/01/rdf-schema#"
    xmlns:crm="http://www.cidoc-crm.org/cidoc-crm/"
    xmlns:crmdig="http://www.cidoc-crm.org/extensions/crmdig/"
    xmlns:dcterms="http://purl.org/dc/terms/"
    exclude-result-prefixes="c">

  <xsl:output method="xml" encoding="UTF-8" indent="yes"/>
  <!-- White space between the carrier's elements is layout, never data (Surrogate parses the
       carrier without it, to keep the tree small; this makes xsltproc read it the same way). -->
  <xsl:strip-space elements="*"/>

  <xsl:param name="crmdig-ns" select="'http://www.cidoc-crm.org/extensions/crmdig/'"/>
  <xsl:param name="base-uri" select="''"/>
  <xsl:param name="package-id" select="''"/>
  <xsl:param name="previous-package-id" select="''"/>

  <xsl:variable name="crm-ns" select="'http://www.cidoc-crm.org/cidoc-crm/'"/>
  <xsl:variable name="xsd" select="'http://www.w3.org/2001/XMLSchema#'"/>
  <xsl:variable name="carrier" select="/c:carrier"/>
  <!-- The capture identifier: the same in every version of the capture's record and in every
       package made of it (the first file is the first photograph, which no run changes);
       mets.xml and bag-info.txt (Surrogate-Capture-Identifier) give the same string. -->
  <xsl:variable name="capture-id">
    <xsl:choose>
      <xsl:when test="$carrier/c:files/c:file"><xsl:value-of select="concat('urn:surrogate:capture:', $carrier/c:files/c:file[1]/@sha256)"/></xsl:when>
      <xsl:otherwise>urn:surrogate:capture:unidentified</xsl:otherwise>
    </xsl:choose>
  </xsl:variable>
  <xsl:variable name="base">
    <xsl:choose>
      <xsl:when test="$base-uri != ''"><xsl:value-of select="$base-uri"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="concat($capture-id, '/')"/></xsl:otherwise>
    </xsl:choose>
  </xsl:variable>
  <!-- Characters not allowed in IRIs, replaced by '_' when a name becomes part of a URI. -->
  <xsl:variable name="unsafe" select="' &quot;#%&lt;&gt;[\]^`{|}/?&amp;'"/>
  <xsl:variable name="safe"   select="'_______________'"/>

  <xsl:key name="person" match="c:creator" use="normalize-space(.)"/>
  <xsl:key name="person" match="c:intervention/@who" use="normalize-space(.)"/>
  <xsl:key name="person" match="c:run/@who" use="normalize-space(.)"/>
  <xsl:key name="camera" match="c:file[@role = 'original']/c:camera"
           use="concat(@make, '|', @model, '|', @serial)"/>
  <xsl:key name="file-by-id" match="c:files/c:file" use="@id"/>
  <xsl:key name="file-by-creator" match="c:files/c:file" use="@createdBy"/>
  <xsl:key name="result-by-step" match="c:data/c:result" use="@step"/>
  <!-- What a step's results name as used (an input file, or an image a per-image result is
       about), keyed by "step-id file-id", and the images ImageDecode decoded: sources are
       selected by testing each file against these keys, which stays linear in the number of
       files (key() given a node-set of N values merges N node-sets, quadratic in libxslt). -->
  <xsl:key name="step-input" match="c:data/c:result/c:input/@file | c:data/c:result/*/@image" use="concat(../../@step, ' ', .)"/>
  <xsl:key name="decoded-image" match="c:data/c:result/c:decoded/@image" use="."/>

  <!-- URIs -->
  <xsl:template name="person-uri">
    <xsl:param name="name"/>
    <xsl:value-of select="concat($base, 'person/', translate(normalize-space($name), $unsafe, $safe))"/>
  </xsl:template>
  <xsl:template name="camera-uri">
    <xsl:param name="camera"/>
    <xsl:value-of select="concat($base, 'device/', translate(concat($camera/@make, '_', $camera/@model, '_', $camera/@serial), $unsafe, $safe))"/>
  </xsl:template>

  <!-- A CRMdig property element (namespace from the crmdig-ns parameter). -->
  <xsl:template name="dig">
    <xsl:param name="p"/>
    <xsl:param name="to"/>
    <xsl:element name="crmdig:{$p}" namespace="{$crmdig-ns}">
      <xsl:attribute name="rdf:resource"><xsl:value-of select="$to"/></xsl:attribute>
    </xsl:element>
  </xsl:template>
  <xsl:template name="dig-type">
    <xsl:param name="class"/>
    <rdf:type rdf:resource="{concat($crmdig-ns, $class)}"/>
  </xsl:template>

  <xsl:template name="time-span">
    <xsl:param name="uri"/>
    <xsl:param name="begin"/>
    <xsl:param name="end"/>
    <crm:P4_has_time-span>
      <crm:E52_Time-Span rdf:about="{$uri}">
        <crm:P82a_begin_of_the_begin rdf:datatype="{$xsd}dateTime"><xsl:value-of select="$begin"/></crm:P82a_begin_of_the_begin>
        <crm:P82b_end_of_the_end rdf:datatype="{$xsd}dateTime"><xsl:value-of select="$end"/></crm:P82b_end_of_the_end>
      </crm:E52_Time-Span>
    </crm:P4_has_time-span>
  </xsl:template>

  <!-- EXIF "YYYY:MM:DD HH:MM:SS" -> "YYYY-MM-DDTHH:MM:SS"; other forms unchanged. -->
  <xsl:template name="exif-date">
    <xsl:param name="d"/>
    <xsl:choose>
      <xsl:when test="string-length($d) &gt;= 19 and substring($d, 5, 1) = ':' and substring($d, 8, 1) = ':'">
        <xsl:value-of select="concat(substring($d, 1, 4), '-', substring($d, 6, 2), '-', substring($d, 9, 2), 'T', substring($d, 12, 8))"/>
      </xsl:when>
      <xsl:otherwise><xsl:value-of select="$d"/></xsl:otherwise>
    </xsl:choose>
  </xsl:template>

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

  <xsl:template match="/">
    <rdf:RDF>
      <xsl:apply-templates select="c:carrier"/>
    </rdf:RDF>
  </xsl:template>

  <xsl:template match="c:carrier">
    <xsl:variable name="originals" select="c:files/c:file[@role = 'original']"/>
    <xsl:variable name="cameras" select="$originals/c:camera[count(. | key('camera', concat(@make, '|', @model, '|', @serial))[1]) = 1]"/>

    <!-- what this document is written in -->
    <rdf:Description rdf:about="{$base}crm.rdf">
      <rdfs:label><xsl:value-of select="concat('CIDOC-CRM description of the capture ', c:header/c:title)"/></rdfs:label>
      <xsl:choose>
        <xsl:when test="$crmdig-ns = 'http://www.cidoc-crm.org/extensions/crmdig/'">
          <rdfs:comment>Classes and properties of CIDOC-CRM 7.1.3 (namespace http://www.cidoc-crm.org/cidoc-crm/) and CRMdig 5.0 (namespace http://www.cidoc-crm.org/extensions/crmdig/); derived from the Surrogate carrier by carrier-to-crm.xsl</rdfs:comment>
          <dcterms:conformsTo rdf:resource="https://cidoc-crm.org/rdfs/7.1.3/CIDOC_CRM_v7.1.3.rdfs"/>
          <dcterms:conformsTo rdf:resource="https://cidoc-crm.org/extensions/crmdig/html/CRMdig_v5.0.html"/>
        </xsl:when>
        <xsl:otherwise>
          <rdfs:comment><xsl:value-of select="concat('Classes and properties of CIDOC-CRM 7.1.3 (namespace http://www.cidoc-crm.org/cidoc-crm/) and CRMdig in the namespace ', $crmdig-ns, ' (the terms of CRMdig 5.0); derived from the Surrogate carrier by carrier-to-crm.xsl')"/></rdfs:comment>
          <dcterms:conformsTo rdf:resource="https://cidoc-crm.org/rdfs/7.1.3/CIDOC_CRM_v7.1.3.rdfs"/>
        </xsl:otherwise>
      </xsl:choose>
    </rdf:Description>

    <!-- the object -->
    <crm:E22_Human-Made_Object rdf:about="{$base}object">
      <rdfs:label><xsl:value-of select="c:header/c:title"/></rdfs:label>
      <crm:P1_is_identified_by>
        <crm:E41_Appellation rdf:about="{$base}object/title">
          <crm:P190_has_symbolic_content><xsl:value-of select="c:header/c:title"/></crm:P190_has_symbolic_content>
        </crm:E41_Appellation>
      </crm:P1_is_identified_by>
      <xsl:for-each select="c:header/c:meta[@key = 'External-Identifier' or @key = 'Object-Identifier']">
        <crm:P1_is_identified_by>
          <crm:E42_Identifier rdf:about="{$base}object/identifier/{position()}">
            <crm:P190_has_symbolic_content><xsl:value-of select="."/></crm:P190_has_symbolic_content>
            <crm:P2_has_type><crm:E55_Type rdf:about="{$base}type/{translate(@key, $unsafe, $safe)}"><rdfs:label><xsl:value-of select="@key"/></rdfs:label></crm:E55_Type></crm:P2_has_type>
          </crm:E42_Identifier>
        </crm:P1_is_identified_by>
      </xsl:for-each>
      <xsl:for-each select="c:header/c:meta[@key != 'External-Identifier' and @key != 'Object-Identifier']">
        <crm:P3_has_note><xsl:value-of select="concat(@key, ': ', .)"/></crm:P3_has_note>
      </xsl:for-each>
    </crm:E22_Human-Made_Object>

    <!-- the rights the depositor stated (option rights) and the licence (option license), which every
         file of the capture is subject to -->
    <xsl:if test="c:header/c:rights or c:header/c:license">
      <crm:E30_Right rdf:about="{$base}rights">
        <rdfs:label><xsl:value-of select="concat('rights in the capture ', c:header/c:title)"/></rdfs:label>
        <xsl:for-each select="c:header/c:rights">
          <crm:P3_has_note><xsl:value-of select="."/></crm:P3_has_note>
        </xsl:for-each>
        <xsl:for-each select="c:header/c:license">
          <crm:P2_has_type>
            <crm:E55_Type rdf:about="{normalize-space(.)}"><rdfs:label><xsl:value-of select="concat('licence ', normalize-space(.))"/></rdfs:label></crm:E55_Type>
          </crm:P2_has_type>
        </xsl:for-each>
      </crm:E30_Right>
    </xsl:if>

    <!-- the session -->
    <crm:E7_Activity rdf:about="{$base}session">
      <rdfs:label><xsl:value-of select="concat('RTI processing: ', c:header/c:title)"/></rdfs:label>
      <!-- The processing continued the photography; it does not consist of it: its time-span
           (when the record was kept) does not contain the shooting, which is earlier and in
           the camera's local time. Its parts are the steps that ran, the command runs and
           the human interventions, all within its time-span. -->
      <crm:P134_continued rdf:resource="{$base}capture"/>
      <xsl:for-each select="c:process/c:step[key('result-by-step', @id)]">
        <crm:P9_consists_of rdf:resource="{$base}step/{@id}"/>
      </xsl:for-each>
      <xsl:for-each select="c:header/c:run">
        <crm:P9_consists_of rdf:resource="{$base}run/{@id}"/>
      </xsl:for-each>
      <xsl:for-each select="c:process/c:step/c:intervention">
        <crm:P9_consists_of rdf:resource="{$base}step/{../@id}/intervention/{count(preceding-sibling::c:intervention) + 1}"/>
      </xsl:for-each>
      <xsl:call-template name="time-span">
        <xsl:with-param name="uri" select="concat($base, 'session/time')"/>
        <xsl:with-param name="begin" select="c:header/c:created"/>
        <xsl:with-param name="end" select="c:header/c:modified"/>
      </xsl:call-template>
    </crm:E7_Activity>

    <!-- the package: a digital object named by its identifier (so the graphs of two packages of
         the capture meet on it), made of the capture's files, about the digitization; a later
         package of the capture shows features of (P130) the one before it -->
    <xsl:if test="$package-id != ''">
      <rdf:Description rdf:about="{$package-id}">
        <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D1_Digital_Object'"/></xsl:call-template>
        <rdfs:label><xsl:value-of select="concat('BagIt package ', $package-id, ' of the capture ', c:header/c:title)"/></rdfs:label>
        <crm:P1_is_identified_by>
          <crm:E42_Identifier rdf:about="{$base}package/identifier">
            <crm:P190_has_symbolic_content><xsl:value-of select="$package-id"/></crm:P190_has_symbolic_content>
            <crm:P2_has_type><crm:E55_Type rdf:about="{$base}type/package-identifier"><rdfs:label>Surrogate package identifier</rdfs:label></crm:E55_Type></crm:P2_has_type>
          </crm:E42_Identifier>
        </crm:P1_is_identified_by>
        <crm:P129_is_about rdf:resource="{$base}capture"/>
        <xsl:for-each select="c:files/c:file">
          <crm:P106_is_composed_of rdf:resource="{$base}file/{@id}"/>
        </xsl:for-each>
        <xsl:if test="$previous-package-id != ''">
          <crm:P130_shows_features_of rdf:resource="{$previous-package-id}"/>
        </xsl:if>
      </rdf:Description>
      <xsl:if test="$previous-package-id != ''">
        <rdf:Description rdf:about="{$previous-package-id}">
          <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D1_Digital_Object'"/></xsl:call-template>
          <rdfs:label><xsl:value-of select="concat('BagIt package ', $previous-package-id, ', made of the capture ', c:header/c:title, ' before its record last changed')"/></rdfs:label>
          <crm:P1_is_identified_by>
            <crm:E42_Identifier rdf:about="{$base}package/previous/identifier">
              <crm:P190_has_symbolic_content><xsl:value-of select="$previous-package-id"/></crm:P190_has_symbolic_content>
              <crm:P2_has_type rdf:resource="{$base}type/package-identifier"/>
            </crm:E42_Identifier>
          </crm:P1_is_identified_by>
        </rdf:Description>
      </xsl:if>
    </xsl:if>

    <!-- the digitization -->
    <rdf:Description rdf:about="{$base}capture">
      <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D2_Digitization_Process'"/></xsl:call-template>
      <rdfs:label><xsl:value-of select="concat('Highlight-RTI capture of ', c:header/c:title, ' (', count($originals), ' images)')"/></rdfs:label>
      <crm:P32_used_general_technique>
        <crm:E55_Type rdf:about="{$base}type/highlight-rti">
          <rdfs:label>Highlight Reflectance Transformation Imaging (H-RTI)</rdfs:label>
        </crm:E55_Type>
      </crm:P32_used_general_technique>
      <crm:P1_is_identified_by>
        <crm:E42_Identifier rdf:about="{$base}capture/identifier">
          <crm:P190_has_symbolic_content><xsl:value-of select="$capture-id"/></crm:P190_has_symbolic_content>
          <crm:P2_has_type><crm:E55_Type rdf:about="{$base}type/capture-identifier"><rdfs:label>Surrogate capture identifier</rdfs:label></crm:E55_Type></crm:P2_has_type>
        </crm:E42_Identifier>
      </crm:P1_is_identified_by>
      <xsl:call-template name="dig"><xsl:with-param name="p" select="'L1_digitized'"/><xsl:with-param name="to" select="concat($base, 'object')"/></xsl:call-template>
      <xsl:for-each select="$cameras">
        <xsl:call-template name="dig">
          <xsl:with-param name="p" select="'L12_happened_on_device'"/>
          <xsl:with-param name="to"><xsl:call-template name="camera-uri"><xsl:with-param name="camera" select="."/></xsl:call-template></xsl:with-param>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:for-each select="c:header/c:creator">
        <crm:P14_carried_out_by>
          <xsl:attribute name="rdf:resource"><xsl:call-template name="person-uri"><xsl:with-param name="name" select="."/></xsl:call-template></xsl:attribute>
        </crm:P14_carried_out_by>
      </xsl:for-each>
      <xsl:for-each select="$originals">
        <xsl:call-template name="dig"><xsl:with-param name="p" select="'L11_had_output'"/><xsl:with-param name="to" select="concat($base, 'file/', @id)"/></xsl:call-template>
      </xsl:for-each>
      <xsl:if test="$originals/c:camera/@dateTimeOriginal">
        <xsl:variable name="first">
          <xsl:for-each select="$originals/c:camera/@dateTimeOriginal"><xsl:sort select="."/><xsl:if test="position() = 1"><xsl:call-template name="exif-date"><xsl:with-param name="d" select="."/></xsl:call-template></xsl:if></xsl:for-each>
        </xsl:variable>
        <xsl:variable name="last">
          <xsl:for-each select="$originals/c:camera/@dateTimeOriginal"><xsl:sort select="."/><xsl:if test="position() = last()"><xsl:call-template name="exif-date"><xsl:with-param name="d" select="."/></xsl:call-template></xsl:if></xsl:for-each>
        </xsl:variable>
        <xsl:call-template name="time-span">
          <xsl:with-param name="uri" select="concat($base, 'capture/time')"/>
          <xsl:with-param name="begin" select="$first"/>
          <xsl:with-param name="end" select="$last"/>
        </xsl:call-template>
      </xsl:if>
    </rdf:Description>

    <!-- the camera(s) -->
    <xsl:for-each select="$cameras">
      <rdf:Description>
        <xsl:attribute name="rdf:about"><xsl:call-template name="camera-uri"><xsl:with-param name="camera" select="."/></xsl:call-template></xsl:attribute>
        <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D8_Digital_Device'"/></xsl:call-template>
        <rdfs:label><xsl:value-of select="normalize-space(concat(@make, ' ', @model))"/></rdfs:label>
        <xsl:if test="@make != ''">
          <crm:P108i_was_produced_by>
            <crm:E12_Production rdf:about="{$base}device/{translate(concat(@make, '_', @model, '_', @serial), $unsafe, $safe)}/production">
              <crm:P14_carried_out_by>
                <crm:E74_Group rdf:about="{$base}maker/{translate(@make, $unsafe, $safe)}"><rdfs:label><xsl:value-of select="@make"/></rdfs:label></crm:E74_Group>
              </crm:P14_carried_out_by>
            </crm:E12_Production>
          </crm:P108i_was_produced_by>
        </xsl:if>
        <xsl:if test="@model != ''">
          <crm:P2_has_type>
            <crm:E55_Type rdf:about="{$base}type/camera-model/{translate(concat(@make, '_', @model), $unsafe, $safe)}"><rdfs:label><xsl:value-of select="normalize-space(concat(@make, ' ', @model))"/></rdfs:label></crm:E55_Type>
          </crm:P2_has_type>
        </xsl:if>
        <xsl:if test="@serial != ''">
          <crm:P1_is_identified_by>
            <crm:E42_Identifier rdf:about="{$base}device/{translate(concat(@make, '_', @model, '_', @serial), $unsafe, $safe)}/serial">
              <crm:P190_has_symbolic_content><xsl:value-of select="@serial"/></crm:P190_has_symbolic_content>
              <crm:P2_has_type><crm:E55_Type rdf:about="{$base}type/serial-number"><rdfs:label>serial number</rdfs:label></crm:E55_Type></crm:P2_has_type>
            </crm:E42_Identifier>
          </crm:P1_is_identified_by>
        </xsl:if>
        <xsl:if test="@lens != ''">
          <crm:P3_has_note><xsl:value-of select="concat('lens: ', @lens)"/></crm:P3_has_note>
        </xsl:if>
      </rdf:Description>
    </xsl:for-each>

    <!-- the workstation -->
    <rdf:Description rdf:about="{$base}machine">
      <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D8_Digital_Device'"/></xsl:call-template>
      <rdfs:label><xsl:value-of select="c:header/c:machine/@hostname"/></rdfs:label>
      <crm:P3_has_note><xsl:value-of select="normalize-space(concat(c:header/c:machine/@os, ', ', c:header/c:machine/@architecture, ', ', c:header/c:machine/@cpu, ', ', c:header/c:machine/@cores, ' cores, ', c:header/c:machine/@memoryBytes, ' bytes of memory'))"/></crm:P3_has_note>
    </rdf:Description>

    <!-- people -->
    <xsl:for-each select="(c:header/c:creator | c:header/c:run/@who | c:process/c:step/c:intervention/@who)[count(. | key('person', normalize-space(.))[1]) = 1]">
      <crm:E21_Person>
        <xsl:attribute name="rdf:about"><xsl:call-template name="person-uri"><xsl:with-param name="name" select="."/></xsl:call-template></xsl:attribute>
        <rdfs:label><xsl:value-of select="normalize-space(.)"/></rdfs:label>
        <crm:P1_is_identified_by>
          <crm:E41_Appellation>
            <xsl:attribute name="rdf:about"><xsl:call-template name="person-uri"><xsl:with-param name="name" select="."/></xsl:call-template>/name</xsl:attribute>
            <crm:P190_has_symbolic_content><xsl:value-of select="normalize-space(.)"/></crm:P190_has_symbolic_content>
          </crm:E41_Appellation>
        </crm:P1_is_identified_by>
        <xsl:for-each select="self::c:creator/@role">
          <crm:P3_has_note><xsl:value-of select="concat('role in the capture: ', .)"/></crm:P3_has_note>
        </xsl:for-each>
      </crm:E21_Person>
    </xsl:for-each>

    <!-- software -->
    <xsl:for-each select="c:header/c:software">
      <rdf:Description rdf:about="{$base}software/{translate(concat(@name, '/', @version), $unsafe, $safe)}">
        <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D14_Software'"/></xsl:call-template>
        <rdfs:label><xsl:value-of select="concat(@name, ' ', @version)"/></rdfs:label>
        <crm:P1_is_identified_by>
          <crm:E41_Appellation rdf:about="{$base}software/{translate(concat(@name, '/', @version), $unsafe, $safe)}/name">
            <crm:P190_has_symbolic_content><xsl:value-of select="@name"/></crm:P190_has_symbolic_content>
          </crm:E41_Appellation>
        </crm:P1_is_identified_by>
        <crm:P2_has_type>
          <crm:E55_Type rdf:about="{$base}software/{translate(concat(@name, '/', @version), $unsafe, $safe)}/version"><rdfs:label><xsl:value-of select="concat('version ', @version)"/></rdfs:label></crm:E55_Type>
        </crm:P2_has_type>
        <xsl:if test="@role != ''"><crm:P3_has_note><xsl:value-of select="@role"/></crm:P3_has_note></xsl:if>
      </rdf:Description>
    </xsl:for-each>

    <xsl:apply-templates select="c:header/c:run"/>
    <xsl:apply-templates select="c:process/c:step"/>
    <xsl:apply-templates select="c:files/c:file"/>
  </xsl:template>

  <!-- The run that made the record's current state: the last completed run (a failed run after
       it left that state in place); with no completed run, the last run (a failed run whose
       partial record is the state). Its P9 parts are the steps that ran (have a result). -->
  <xsl:variable name="state-run">
    <xsl:choose>
      <xsl:when test="$carrier/c:header/c:run[@outcome = 'completed']"><xsl:value-of select="$carrier/c:header/c:run[@outcome = 'completed'][last()]/@id"/></xsl:when>
      <xsl:otherwise><xsl:value-of select="$carrier/c:header/c:run[last()]/@id"/></xsl:otherwise>
    </xsl:choose>
  </xsl:variable>

  <!-- a command run: the history of the record -->
  <xsl:template match="c:run">
    <xsl:variable name="uri" select="concat($base, 'run/', @id)"/>
    <crm:E7_Activity rdf:about="{$uri}">
      <rdfs:label><xsl:value-of select="concat('surrogate ', @command, ' (', @id, ')')"/></rdfs:label>
      <crm:P2_has_type>
        <crm:E55_Type rdf:about="{$base}type/surrogate-run"><rdfs:label>Surrogate command run</rdfs:label></crm:E55_Type>
      </crm:P2_has_type>
      <crm:P2_has_type>
        <crm:E55_Type rdf:about="{$base}type/command/{translate(@command, $unsafe, $safe)}"><rdfs:label><xsl:value-of select="concat('surrogate ', @command)"/></rdfs:label></crm:E55_Type>
      </crm:P2_has_type>
      <crm:P2_has_type>
        <crm:E55_Type rdf:about="{$base}type/run-outcome/{@outcome}"><rdfs:label><xsl:value-of select="concat('run outcome: ', @outcome)"/></rdfs:label></crm:E55_Type>
      </crm:P2_has_type>
      <crm:P14_carried_out_by>
        <xsl:attribute name="rdf:resource"><xsl:call-template name="person-uri"><xsl:with-param name="name" select="@who"/></xsl:call-template></xsl:attribute>
      </crm:P14_carried_out_by>
      <crm:P3_has_note>
        <xsl:text>command line: </xsl:text>
        <xsl:call-template name="command-line"><xsl:with-param name="run" select="."/></xsl:call-template>
      </crm:P3_has_note>
      <crm:P3_has_note><xsl:value-of select="concat('outcome: ', @outcome)"/></crm:P3_has_note>
      <xsl:for-each select="c:note">
        <crm:P3_has_note><xsl:value-of select="."/></crm:P3_has_note>
      </xsl:for-each>
      <xsl:for-each select="preceding-sibling::c:run[1]">
        <crm:P134_continued rdf:resource="{$base}run/{@id}"/>
      </xsl:for-each>
      <xsl:if test="@id = $state-run">
        <xsl:for-each select="$carrier/c:process/c:step[@id = $carrier/c:data/c:result/@step]">
          <crm:P9_consists_of rdf:resource="{$base}step/{@id}"/>
        </xsl:for-each>
      </xsl:if>
      <xsl:call-template name="time-span">
        <xsl:with-param name="uri" select="concat($uri, '/time')"/>
        <xsl:with-param name="begin" select="@started"/>
        <xsl:with-param name="end" select="@ended"/>
      </xsl:call-template>
    </crm:E7_Activity>
  </xsl:template>

  <!-- a pipeline step -->
  <xsl:template match="c:step">
    <xsl:variable name="step" select="."/>
    <xsl:variable name="uri" select="concat($base, 'step/', @id)"/>
    <xsl:variable name="result" select="$carrier/c:data/c:result[@step = $step/@id]"/>
    <rdf:Description rdf:about="{$uri}">
      <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D10_Software_Execution'"/></xsl:call-template>
      <rdfs:label><xsl:value-of select="concat(@id, ': ', @component, ' ', @version)"/></rdfs:label>
      <xsl:if test="c:description != ''"><crm:P3_has_note><xsl:value-of select="normalize-space(c:description)"/></crm:P3_has_note></xsl:if>
      <xsl:if test="@algorithm != ''">
        <crm:P33_used_specific_technique>
          <crm:E29_Design_or_Procedure rdf:about="{$base}technique/{translate(@algorithm, $unsafe, $safe)}"><rdfs:label><xsl:value-of select="@algorithm"/></rdfs:label></crm:E29_Design_or_Procedure>
        </crm:P33_used_specific_technique>
      </xsl:if>
      <xsl:call-template name="dig"><xsl:with-param name="p" select="'L23_used_software_or_firmware'"/><xsl:with-param name="to" select="concat($uri, '/software')"/></xsl:call-template>
      <xsl:for-each select="$carrier/c:header/c:software">
        <xsl:call-template name="dig"><xsl:with-param name="p" select="'L23_used_software_or_firmware'"/><xsl:with-param name="to" select="concat($base, 'software/', translate(concat(@name, '/', @version), $unsafe, $safe))"/></xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="dig"><xsl:with-param name="p" select="'L12_happened_on_device'"/><xsl:with-param name="to" select="concat($base, 'machine')"/></xsl:call-template>
      <xsl:if test="c:param">
        <xsl:call-template name="dig"><xsl:with-param name="p" select="'L13_used_parameters'"/><xsl:with-param name="to" select="concat($uri, '/parameters')"/></xsl:call-template>
      </xsl:if>
      <!-- What the step used: the same expression as carrier-to-mets.xsl's step-sources (see
           there and mappings/carrier-to-crm.md). -->
      <xsl:variable name="explicit" select="boolean($result/c:input/@file or $result/*/@image)"/>
      <xsl:variable name="decodeIds" select="$carrier/c:process/c:step[@component = 'ImageDecode']/@id"/>
      <xsl:variable name="useDecoded" select="(not($explicit) or ($step/@component = 'ColourCorrection' and $result/c:value[@name = 'outcome']/@value = 'corrected')) and $step/@component != 'CaptureIngest' and $step/@component != 'ImageDecode' and $step/@component != 'DerivedMaps'"/>
      <xsl:variable name="lights" select="key('result-by-step', $step/preceding-sibling::c:step[@component = 'LightDirections' or @component = 'LightsFromFile']/@id)/c:output[@kind = 'lp']/@file[$step/@component = 'RtiFit']"/>
      <xsl:variable name="model" select="key('result-by-step', $step/preceding-sibling::c:step[@component = 'RtiFit'][c:param[@name = 'basis']/@value = $step/c:param[@name = 'model']/@value]/@id)/c:output/@file[$step/@component = 'DerivedMaps']"/>
      <xsl:variable name="sources" select="$carrier/c:files/c:file[
          key('step-input', concat($step/@id, ' ', @id))
          or ($useDecoded and key('decoded-image', @id)[../../@step = $decodeIds])
          or @id = $lights or @id = $model]"/>
      <xsl:if test="$result">
        <xsl:for-each select="$sources">
          <xsl:call-template name="dig"><xsl:with-param name="p" select="'L10_had_input'"/><xsl:with-param name="to" select="concat($base, 'file/', @id)"/></xsl:call-template>
        </xsl:for-each>
      </xsl:if>
      <xsl:for-each select="key('file-by-id', $result/c:output/@file) | key('file-by-creator', @id)">
        <xsl:call-template name="dig"><xsl:with-param name="p" select="'L11_had_output'"/><xsl:with-param name="to" select="concat($base, 'file/', @id)"/></xsl:call-template>
      </xsl:for-each>
      <xsl:for-each select="preceding-sibling::c:step[1]">
        <crm:P134_continued rdf:resource="{$base}step/{@id}"/>
      </xsl:for-each>
      <!-- A decision by hand steered the step; it was taken when the command was given,
           before the step ran, so it is not a part of the step (P9 would nest time-spans). -->
      <xsl:for-each select="c:intervention">
        <crm:P17_was_motivated_by rdf:resource="{$uri}/intervention/{position()}"/>
      </xsl:for-each>
      <xsl:if test="$result">
        <crm:P3_has_note><xsl:value-of select="concat('status: ', $result/@status, '; seconds: ', $result/@seconds)"/></crm:P3_has_note>
        <xsl:call-template name="time-span">
          <xsl:with-param name="uri" select="concat($uri, '/time')"/>
          <xsl:with-param name="begin" select="$result/@started"/>
          <xsl:with-param name="end" select="$result/@ended"/>
        </xsl:call-template>
        <xsl:for-each select="$result/c:value">
          <crm:P3_has_note><xsl:value-of select="normalize-space(concat('result ', @name, ' = ', @value, ' ', @unit))"/></crm:P3_has_note>
        </xsl:for-each>
      </xsl:if>
      <xsl:if test="@component = 'ColourCorrection' and $result/c:value[@name = 'outcome']/@value = 'corrected'">
        <xsl:call-template name="colour-correction"><xsl:with-param name="result" select="$result"/><xsl:with-param name="uri" select="$uri"/></xsl:call-template>
      </xsl:if>
    </rdf:Description>

    <!-- the component as software -->
    <rdf:Description rdf:about="{$uri}/software">
      <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D14_Software'"/></xsl:call-template>
      <rdfs:label><xsl:value-of select="concat('Surrogate ', @component, ' ', @version)"/></rdfs:label>
      <crm:P1_is_identified_by>
        <crm:E41_Appellation rdf:about="{$uri}/software/name">
          <crm:P190_has_symbolic_content><xsl:value-of select="@component"/></crm:P190_has_symbolic_content>
        </crm:E41_Appellation>
      </crm:P1_is_identified_by>
      <crm:P2_has_type>
        <crm:E55_Type rdf:about="{$uri}/software/version"><rdfs:label><xsl:value-of select="concat('version ', @version)"/></rdfs:label></crm:E55_Type>
      </crm:P2_has_type>
    </rdf:Description>

    <!-- its parameters -->
    <xsl:if test="c:param">
      <rdf:Description rdf:about="{$uri}/parameters">
        <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D1_Digital_Object'"/></xsl:call-template>
        <rdfs:label><xsl:value-of select="concat('parameters of ', @id, ' (', @component, ')')"/></rdfs:label>
        <xsl:for-each select="c:param">
          <crm:P106_is_composed_of>
            <rdf:Description rdf:about="{$uri}/parameter/{translate(@name, $unsafe, $safe)}">
              <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D1_Digital_Object'"/></xsl:call-template>
              <rdfs:label><xsl:value-of select="@name"/></rdfs:label>
              <crm:P190_has_symbolic_content><xsl:value-of select="concat(@name, '=', @value)"/></crm:P190_has_symbolic_content>
            </rdf:Description>
          </crm:P106_is_composed_of>
        </xsl:for-each>
      </rdf:Description>
    </xsl:if>

    <!-- human interventions -->
    <xsl:for-each select="c:intervention">
      <crm:E7_Activity rdf:about="{$uri}/intervention/{position()}">
        <rdfs:label><xsl:value-of select="concat(@kind, ' on ', @target)"/></rdfs:label>
        <crm:P2_has_type>
          <crm:E55_Type rdf:about="{$base}type/intervention/{translate(@kind, $unsafe, $safe)}"><rdfs:label><xsl:value-of select="@kind"/></rdfs:label></crm:E55_Type>
        </crm:P2_has_type>
        <crm:P14_carried_out_by>
          <xsl:attribute name="rdf:resource"><xsl:call-template name="person-uri"><xsl:with-param name="name" select="@who"/></xsl:call-template></xsl:attribute>
        </crm:P14_carried_out_by>
        <crm:P3_has_note><xsl:value-of select="concat('reason: ', normalize-space(.))"/></crm:P3_has_note>
        <xsl:choose>
          <xsl:when test="@kind = 'accept-changed-original' and @value = 'removed'"><crm:P3_has_note>accepted: the file is removed</crm:P3_has_note></xsl:when>
          <xsl:when test="@kind = 'accept-changed-original' and @value != ''"><crm:P3_has_note><xsl:value-of select="concat('accepted: the file as it is now, ', @value)"/></crm:P3_has_note></xsl:when>
          <xsl:when test="@value != ''"><crm:P3_has_note><xsl:value-of select="concat('value chosen: ', @value)"/></crm:P3_has_note></xsl:when>
        </xsl:choose>
        <xsl:call-template name="time-span">
          <xsl:with-param name="uri" select="concat($uri, '/intervention/', position(), '/time')"/>
          <xsl:with-param name="begin" select="@time"/>
          <xsl:with-param name="end" select="@time"/>
        </xsl:call-template>
      </crm:E7_Activity>
    </xsl:for-each>
  </xsl:template>

  <!-- Colour from a chart (a ColourCorrection step that corrected; mappings/carrier-to-crm.md,
       "Colour correction"), said of its step: it used a chart of the edition the reference
       values belong to (P125, an E55 named by the reference) and the correction model (P33, an
       E29); it consists of (P9) the measurement (E16) of the chart image (P39) whose observed
       dimensions (P40, E54) are the CIEDE2000 figures, before, after and held out, in the unit
       CIEDE2000 (E58), with the quality levels they reach as notes. The coefficients and the
       per-patch values are the step's notes and the carrier's. -->
  <xsl:template name="colour-correction">
    <xsl:param name="result"/>
    <xsl:param name="uri"/>
    <xsl:variable name="reference" select="$result/c:value[@name = 'reference']/@value"/>
    <xsl:variable name="model" select="$result/c:value[@name = 'model']/@value"/>
    <crm:P125_used_object_of_type>
      <crm:E55_Type rdf:about="{$base}type/colour-chart/{translate($reference, $unsafe, $safe)}">
        <rdfs:label><xsl:value-of select="$result/c:value[@name = 'referenceTitle']/@value"/></rdfs:label>
        <xsl:for-each select="$result/c:value[@name = 'referenceSource']">
          <crm:P3_has_note><xsl:value-of select="concat('reference values (', $reference, '): ', @value)"/></crm:P3_has_note>
        </xsl:for-each>
      </crm:E55_Type>
    </crm:P125_used_object_of_type>
    <crm:P33_used_specific_technique>
      <crm:E29_Design_or_Procedure rdf:about="{$base}technique/colour-model/{translate($model, $unsafe, $safe)}">
        <rdfs:label><xsl:value-of select="concat('colour correction model ', $model, ' (linear light, fitted to the chart)')"/></rdfs:label>
      </crm:E29_Design_or_Procedure>
    </crm:P33_used_specific_technique>
    <crm:P9_consists_of>
      <crm:E16_Measurement rdf:about="{$uri}/colour-accuracy">
        <rdfs:label><xsl:value-of select="concat('colour accuracy of ', $result/@step, ' on the chart (CIEDE2000 to the reference values)')"/></rdfs:label>
        <xsl:for-each select="$result/c:input[@kind = 'chart']">
          <crm:P39_measured rdf:resource="{$base}file/{@file}"/>
        </xsl:for-each>
        <xsl:for-each select="$result/c:value[starts-with(@name, 'deltaE2000')][number(@value) = number(@value)]">
          <crm:P40_observed_dimension>
            <crm:E54_Dimension rdf:about="{$uri}/colour-accuracy/{@name}">
              <crm:P2_has_type>
                <crm:E55_Type rdf:about="{$base}type/dimension/{@name}">
                  <rdfs:label>
                    <xsl:choose>
                      <xsl:when test="starts-with(@name, 'deltaE2000Mean')">CIEDE2000 mean</xsl:when>
                      <xsl:otherwise>CIEDE2000 max</xsl:otherwise>
                    </xsl:choose>
                    <xsl:choose>
                      <xsl:when test="contains(@name, 'Before')"> before correction</xsl:when>
                      <xsl:when test="contains(@name, 'HeldOut')"> held out (each patch corrected by a fit without it)</xsl:when>
                      <xsl:otherwise> after correction</xsl:otherwise>
                    </xsl:choose>
                  </rdfs:label>
                </crm:E55_Type>
              </crm:P2_has_type>
              <crm:P90_has_value rdf:datatype="{$xsd}decimal"><xsl:value-of select="@value"/></crm:P90_has_value>
              <crm:P91_has_unit><crm:E58_Measurement_Unit rdf:about="{$base}unit/CIEDE2000"><rdfs:label>CIEDE2000 colour difference (CIE 142-2001)</rdfs:label></crm:E58_Measurement_Unit></crm:P91_has_unit>
            </crm:E54_Dimension>
          </crm:P40_observed_dimension>
        </xsl:for-each>
        <xsl:for-each select="$result/c:value[@name = 'qualityLevel']">
          <crm:P3_has_note><xsl:value-of select="concat('quality level: ', @value)"/></crm:P3_has_note>
        </xsl:for-each>
      </crm:E16_Measurement>
    </crm:P9_consists_of>
  </xsl:template>

  <!-- a file -->
  <xsl:template match="c:file">
    <xsl:variable name="uri" select="concat($base, 'file/', @id)"/>
    <rdf:Description rdf:about="{$uri}">
      <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D9_Data_Object'"/></xsl:call-template>
      <rdfs:label><xsl:value-of select="@path"/></rdfs:label>
      <crm:P1_is_identified_by>
        <crm:E42_Identifier rdf:about="{$uri}/path">
          <crm:P190_has_symbolic_content><xsl:value-of select="concat('data/', @path)"/></crm:P190_has_symbolic_content>
          <crm:P2_has_type><crm:E55_Type rdf:about="{$base}type/bag-path"><rdfs:label>path in the BagIt package</rdfs:label></crm:E55_Type></crm:P2_has_type>
        </crm:E42_Identifier>
      </crm:P1_is_identified_by>
      <crm:P1_is_identified_by>
        <crm:E42_Identifier rdf:about="{$uri}/sha256">
          <crm:P190_has_symbolic_content><xsl:value-of select="@sha256"/></crm:P190_has_symbolic_content>
          <crm:P2_has_type><crm:E55_Type rdf:about="{$base}type/sha256"><rdfs:label>SHA-256 checksum</rdfs:label></crm:E55_Type></crm:P2_has_type>
        </crm:E42_Identifier>
      </crm:P1_is_identified_by>
      <crm:P43_has_dimension>
        <crm:E54_Dimension rdf:about="{$uri}/size">
          <crm:P2_has_type><crm:E55_Type rdf:about="{$base}type/file-size"><rdfs:label>file size</rdfs:label></crm:E55_Type></crm:P2_has_type>
          <crm:P90_has_value rdf:datatype="{$xsd}decimal"><xsl:value-of select="@size"/></crm:P90_has_value>
          <crm:P91_has_unit><crm:E58_Measurement_Unit rdf:about="{$base}unit/byte"><rdfs:label>byte</rdfs:label></crm:E58_Measurement_Unit></crm:P91_has_unit>
        </crm:E54_Dimension>
      </crm:P43_has_dimension>
      <crm:P2_has_type>
        <crm:E55_Type rdf:about="{$base}type/format/{translate(@format, $unsafe, $safe)}">
          <rdfs:label><xsl:value-of select="@format"/></rdfs:label>
          <xsl:if test="@puid != ''"><crm:P3_has_note><xsl:value-of select="concat('PRONOM ', @puid)"/></crm:P3_has_note></xsl:if>
          <xsl:if test="@mediaType != ''"><crm:P3_has_note><xsl:value-of select="concat('media type ', @mediaType)"/></crm:P3_has_note></xsl:if>
        </crm:E55_Type>
      </crm:P2_has_type>
      <xsl:if test="$carrier/c:header/c:rights or $carrier/c:header/c:license">
        <crm:P104_is_subject_to rdf:resource="{$base}rights"/>
      </xsl:if>
      <crm:P2_has_type>
        <crm:E55_Type rdf:about="{$base}type/role/{@role}"><rdfs:label><xsl:value-of select="concat('file role: ', @role)"/></rdfs:label></crm:E55_Type>
      </crm:P2_has_type>
      <xsl:if test="@role = 'result'">
        <!-- a result is an image of the object: P138's domain is E36 Visual Item -->
        <rdf:type rdf:resource="{$crm-ns}E36_Visual_Item"/>
        <crm:P138_represents rdf:resource="{$base}object"/>
      </xsl:if>
      <xsl:if test="@role = 'result' and starts-with(@path, 'finished-files/web/')">
        <!-- the web copy of a model (surrogate run with publish): the access copy of the package -->
        <crm:P3_has_note><xsl:value-of select="concat('web access copy of the model (info.json, JPEG coefficient planes and a viewer that OpenLIME and Relight read): ', @format)"/></crm:P3_has_note>
      </xsl:if>
      <xsl:for-each select="@pairedWith">
        <crm:P130_shows_features_of rdf:resource="{$base}file/{.}"/>
      </xsl:for-each>
      <xsl:if test="@unrecordedProcessing = 'true' or @unrecordedProcessing = '1'">
        <crm:P3_has_note>made by other software; its processing is not recorded in the carrier</crm:P3_has_note>
      </xsl:if>
      <xsl:if test="@role = 'prior'">
        <crm:P3_has_note><xsl:value-of select="concat('prior work (', @priorKind, '): made outside Surrogate by another tool; no recorded Surrogate event produced it')"/></crm:P3_has_note>
      </xsl:if>

      <xsl:for-each select="c:image">
        <crm:P3_has_note><xsl:value-of select="concat('image ', @width, ' x ', @height, ' pixels')"/></crm:P3_has_note>
      </xsl:for-each>
      <xsl:for-each select="c:camera">
        <crm:P3_has_note>
          <xsl:text>camera settings:</xsl:text>
          <xsl:for-each select="@*"><xsl:value-of select="concat(' ', local-name(), '=', .)"/></xsl:for-each>
        </crm:P3_has_note>
      </xsl:for-each>
      <xsl:if test="c:xmp != ''">
        <crm:P3_has_note><xsl:value-of select="concat('XMP packet of ', string-length(c:xmp), ' characters, kept verbatim in the carrier')"/></crm:P3_has_note>
      </xsl:if>
    </rdf:Description>
    <!-- an export made by other software from the original of the same shot: the machine
         event that made it, with what it read; when, how and with what is not on record -->
    <xsl:if test="(@unrecordedProcessing = 'true' or @unrecordedProcessing = '1') and key('file-by-id', @pairedWith)/@role = 'original'">
      <rdf:Description rdf:about="{$uri}/made-elsewhere">
        <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D7_Digital_Machine_Event'"/></xsl:call-template>
        <rdfs:label><xsl:value-of select="concat('export of ', key('file-by-id', @pairedWith)/@path, ' by other software')"/></rdfs:label>
        <xsl:call-template name="dig"><xsl:with-param name="p" select="'L10_had_input'"/><xsl:with-param name="to" select="concat($base, 'file/', @pairedWith)"/></xsl:call-template>
        <xsl:call-template name="dig"><xsl:with-param name="p" select="'L11_had_output'"/><xsl:with-param name="to" select="$uri"/></xsl:call-template>
        <crm:P3_has_note>made by software other than Surrogate; what it did, when and with which settings is not recorded</crm:P3_has_note>
      </rdf:Description>
    </xsl:if>
    <!-- prior work: the machine event of another tool that made it, of which only what the
         file itself says is known (madeBy) -->
    <xsl:if test="@role = 'prior'">
      <rdf:Description rdf:about="{$uri}/made-elsewhere">
        <xsl:call-template name="dig-type"><xsl:with-param name="class" select="'D7_Digital_Machine_Event'"/></xsl:call-template>
        <rdfs:label><xsl:value-of select="concat('making of ', @path, ' by another tool (prior work)')"/></rdfs:label>
        <xsl:call-template name="dig"><xsl:with-param name="p" select="'L11_had_output'"/><xsl:with-param name="to" select="$uri"/></xsl:call-template>
        <crm:P3_has_note>made by software other than Surrogate before this record; what it did, when and with which settings is not recorded</crm:P3_has_note>
        <xsl:if test="@madeBy != ''">
          <crm:P3_has_note><xsl:value-of select="concat('the file says of its making: ', @madeBy)"/></crm:P3_has_note>
        </xsl:if>
      </rdf:Description>
    </xsl:if>
  </xsl:template>

</xsl:stylesheet>
