<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>
<!-- Fallback style applied by the urbanvec plugin when the output carries no layer_styles entry. -->
<qgis version="3.22.0" styleCategories="Symbology">
  <pipe>
    <rasterrenderer type="paletted" band="1" opacity="1" alphaBand="-1" nodataColor="">
      <colorPalette>
        <paletteEntry value="0" label="Unused" color="#ffffff" alpha="0"/>
        <paletteEntry value="1" label="Water" color="#78b4e6" alpha="255"/>
        <paletteEntry value="2" label="Secondary road" color="#5a5a5a" alpha="255"/>
        <paletteEntry value="3" label="Primary road" color="#c85a28" alpha="255"/>
        <paletteEntry value="4" label="Residential" color="#f6e05e" alpha="255"/>
        <paletteEntry value="5" label="Commercial" color="#e04040" alpha="255"/>
        <paletteEntry value="6" label="Industrial" color="#466edc" alpha="255"/>
        <paletteEntry value="7" label="Park" color="#5ab45a" alpha="255"/>
        <paletteEntry value="8" label="Reserved" color="#aaaaaa" alpha="255"/>
      </colorPalette>
    </rasterrenderer>
  </pipe>
</qgis>
