# Included by ctest after the discovered tests (TEST_INCLUDE_FILES): the tests labelled
# "large", which the sanitizer run (test preset fuzz, .ci/run's second step) leaves out, as it
# leaves out the CLI's tests (the preset does not build the CLI). A test is large when it runs
# whole pipelines over phantoms many times: ASan+UBSan make those 10-20x slower, past half a
# minute each, while the release suite runs every one of them and the sanitizer run keeps the
# smaller tests of the same code. `ctest --preset fuzz` lists the rest.
set_tests_properties(SurfacesTest.Volume512x512x400WorksInSlabs Assembly.RandomVolumesAreWellFormed
  Smoothing.PhantomNeverCrosses Remesh.Phantom RemeshBuildTest.BuildRemeshesThePhantomAfterSmoothing
  InterpolatedShapesTest.FinerGridsNeverIncreaseTheSphereError Remesh.SameResultForAnyThreadCount
  IncidentalOverlapsTest.IndependentlyDrawnNeighboursShareOneSurface IncidentalOverlapsTest.ThreeNeighboursMeetingAtAJunction
  InterpolationVolumeTest.FewPlaneStructuresKeepTheirSlabVolume IncidentalOverlapsTest.SplitOnTheDeviceEqualsTheHostRoundTrip
  InterpolatedShapesTest.AccuracyAtThreeGridsAgainstOff InterpolationVolumeTest.VolumesDoNotDependOnTheOtherStructures
  GridSweepTest.EveryShapeIsRightAtEveryGrid IncidentalOverlapsTest.ADeepPokeIsRealOnlyWhenNotTiny
  RemeshChunks.PhantomInChunksKeepsEveryGuarantee RemeshChunks.SameResultOnAnyThreadCount
  InterpolationVolumeTest.FewPlaneStructuresKeepTheirBatchVolume SurfacesTest.TheWholeRunIsTheSameOnOneTwoAndThreeThreads
  PROPERTIES LABELS large)
