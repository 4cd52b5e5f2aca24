// expect: 'Plugin' runs a post-processing plugin
Plugin(CutPlane).Run;
